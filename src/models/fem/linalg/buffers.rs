//! A per-thread pool of the band matrices' storage: a solve allocates its tangent and factor
//! (for a BHA model ~170 kB each) and frees them at the end; allocations that large are
//! mapped fresh from the operating system each time, so every page is faulted in again on
//! every solve (about a tenth of a warm-started BHA solve). Freed storage up to
//! [`MAX_POOLED_BYTES`] is kept here (at most [`MAX_POOLED`] buffers per thread) and handed to
//! the next matrix of the same or a smaller size.

use std::cell::RefCell;

/// Largest buffer kept, bytes (a band of ~5,000 DOF: BHA and short-string models).
pub const MAX_POOLED_BYTES: usize = 1 << 20;
/// Buffers kept per thread.
pub const MAX_POOLED: usize = 8;

thread_local! {
    static POOL: RefCell<Vec<Vec<f64>>> = const { RefCell::new(Vec::new()) };
}

/// A vector of `len` zeros, from the pool when it holds one large enough.
pub fn zeroed(len: usize) -> Vec<f64> {
    let mut v = reused(len);
    v.fill(0.0);
    v
}

/// A vector of length `len` whose values are unspecified (leftovers of an earlier use, not
/// necessarily finite, or zeros): for storage that is completely written before it is read.
pub fn for_overwrite(len: usize) -> Vec<f64> {
    reused(len)
}

fn reused(len: usize) -> Vec<f64> {
    let found = POOL
        .try_with(|p| {
            let mut p = p.borrow_mut();
            // the smallest buffer that fits
            let best = p
                .iter()
                .enumerate()
                .filter(|(_, v)| v.capacity() >= len)
                .min_by_key(|(_, v)| v.capacity())
                .map(|(k, _)| k);
            best.map(|k| p.swap_remove(k))
        })
        .ok()
        .flatten();
    match found {
        Some(mut v) => {
            v.truncate(len);
            v.resize(len, 0.0);
            v
        }
        None => vec![0.0; len],
    }
}

/// Return `v`'s storage to the pool (dropped instead when it is too large or the pool full).
pub fn give_back(v: Vec<f64>) {
    if v.capacity() == 0 || v.capacity() * std::mem::size_of::<f64>() > MAX_POOLED_BYTES {
        return;
    }
    let _ = POOL.try_with(|p| {
        let mut p = p.borrow_mut();
        if p.len() < MAX_POOLED {
            p.push(v);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reused_storage_is_zeroed_and_sized() {
        // Reference: a fresh `vec![0.0; len]`; a returned buffer full of ones must come back
        // as zeros of the requested length, and its storage must be the one reused.
        let mut v = vec![1.0; 1000];
        v[999] = f64::NAN;
        let ptr = v.as_ptr();
        give_back(v);
        let w = zeroed(600);
        assert_eq!(w.len(), 600);
        assert!(w.iter().all(|&x| x == 0.0));
        assert_eq!(w.as_ptr(), ptr, "the pooled storage is reused");
        give_back(w);
        let u = for_overwrite(1000);
        assert_eq!(u.len(), 1000);
        give_back(u);
        // too large: not kept; the pool never grows past MAX_POOLED
        let pooled = || POOL.with(|p| p.borrow().len());
        let before = pooled();
        give_back(vec![0.0; MAX_POOLED_BYTES / 8 + 1]);
        assert_eq!(pooled(), before);
        for _ in 0..2 * MAX_POOLED {
            give_back(vec![0.0; 10]);
        }
        assert_eq!(pooled(), MAX_POOLED);
    }
}
