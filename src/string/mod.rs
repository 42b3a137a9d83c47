//! The drill string: components from the bit upward, materials, section properties.

pub mod component;
pub mod material;

pub use component::{Component, ComponentKind, MotorBend, RssSteer, RssTool, MAX_BEND_ANGLE_RAD};
pub use material::Material;

/// Components from the bit upward, contiguous (`components[k+1].bottom_m == components[k].top_m()`).
#[derive(Debug, Clone, PartialEq)]
pub struct DrillString {
    /// Components from the bit upward.
    pub components: Vec<Component>,
}

impl DrillString {
    /// The string with its bit at `bit_md_m` (distance to surface `bit_md_m`, m): components from
    /// the bit upward as in this string; the topmost one is resized so that the string reaches the
    /// surface, or the string is cut at the surface when the lower components are already longer.
    ///
    /// # Panics
    /// If this string has no components or `bit_md_m` is not positive.
    pub fn at_depth(&self, bit_md_m: f64) -> DrillString {
        assert!(!self.components.is_empty() && bit_md_m > 0.0);
        let mut comps = Vec::with_capacity(self.components.len());
        let last = self.components.len() - 1;
        for (k, c) in self.components.iter().enumerate() {
            if c.bottom_m >= bit_md_m - 1e-9 {
                break;
            }
            let mut c = c.clone();
            if k == last || c.top_m() > bit_md_m {
                c.length_m = bit_md_m - c.bottom_m;
            }
            let done = c.top_m() >= bit_md_m - 1e-9;
            comps.push(c);
            if done {
                break;
            }
        }
        DrillString { components: comps }
    }

    /// Total length from the bit face to the top, m.
    pub fn length_m(&self) -> f64 {
        self.components.last().map(|c| c.top_m()).unwrap_or(0.0)
    }
    /// The component at distance `x_m` from the bit face (the upper one at a boundary's top side).
    pub fn component_at(&self, x_m: f64) -> &Component {
        self.components
            .iter()
            .find(|c| x_m < c.top_m())
            .unwrap_or_else(|| self.components.last().expect("a string has components"))
    }
    /// Bit diameter, m: the contact OD of the bit component, if the string starts with one.
    pub fn bit_diameter_m(&self) -> Option<f64> {
        self.components
            .first()
            .filter(|c| c.kind == ComponentKind::Bit)
            .map(|c| c.contact_od_m)
    }
    /// Length of the bottom-hole assembly: from the bit to the top of the highest component
    /// that is not pipe or HWDP, m.
    pub fn bha_length_m(&self) -> f64 {
        self.components
            .iter()
            .filter(|c| c.is_bha())
            .map(|c| c.top_m())
            .fold(0.0, f64::max)
    }
    /// The bottom `length_m` of the string (components above dropped, the one crossing the cut
    /// shortened); the whole string if it is not longer.
    pub fn truncated(&self, length_m: f64) -> DrillString {
        let mut components = Vec::new();
        for c in &self.components {
            if c.bottom_m >= length_m - 1e-9 {
                break;
            }
            let mut c = c.clone();
            c.length_m = c.length_m.min(length_m - c.bottom_m);
            components.push(c);
        }
        DrillString { components }
    }
    /// The bent housing of the string (the first motor with a bend), if any.
    pub fn bend(&self) -> Option<MotorBend> {
        self.components.iter().find_map(|c| c.bend)
    }
    /// The rotary steerable system of the string (the first `rss` component's), if any.
    pub fn rss(&self) -> Option<RssTool> {
        self.components.iter().find_map(|c| c.rss)
    }
    /// The kink of the string's unloaded axis: a bent housing's bend, or a point-the-bit
    /// tool's hinge with its deflection (None when the string has neither).
    pub fn kink(&self) -> Option<MotorBend> {
        self.bend().or_else(|| self.rss().and_then(|r| r.kink()))
    }
    /// The string with its rotary steerable system neutral ([`RssTool::neutral`]); the same
    /// string without one.
    pub fn rss_neutral(&self) -> DrillString {
        let mut s = self.clone();
        for c in &mut s.components {
            c.rss = c.rss.map(|r| r.neutral());
        }
        s
    }
    /// The string with its rotary steerable system's ratio set to `ratio` (no effect without
    /// one).
    pub fn with_rss_ratio(&self, ratio: f64) -> DrillString {
        let mut s = self.clone();
        for c in &mut s.components {
            if let Some(r) = c.rss.as_mut() {
                r.ratio = ratio;
            }
        }
        s
    }
    /// The index of the pad stabilizer of the bent housing: the `stabilizer` component nearest
    /// the bend whose middle lies below it (None without a bend or without such a stabilizer).
    pub fn pad_index(&self) -> Option<usize> {
        let bend = self.bend()?;
        self.components
            .iter()
            .enumerate()
            .filter(|(_, c)| c.kind == ComponentKind::Stabilizer)
            .rfind(|(_, c)| c.bottom_m + c.length_m / 2.0 < bend.to_bit_m)
            .map(|(k, _)| k)
    }
    /// The blade OD of the bent housing's pad stabilizer ([`DrillString::pad_index`]), m.
    pub fn pad_od_m(&self) -> Option<f64> {
        self.pad_index().map(|k| self.components[k].contact_od_m)
    }
    /// The string with the blade OD of its pad stabilizer set to `od_m` (m; no effect without
    /// a pad).
    pub fn with_pad_od(&self, od_m: f64) -> DrillString {
        let mut s = self.clone();
        if let Some(k) = self.pad_index() {
            s.components[k].contact_od_m = od_m;
        }
        s
    }
    /// Distances from the bit of stabilizer contact points (mid-length), m.
    pub fn stabilizer_contacts_m(&self) -> Vec<f64> {
        self.components
            .iter()
            .filter(|c| c.kind == ComponentKind::Stabilizer)
            .map(|c| c.bottom_m + c.length_m / 2.0)
            .collect()
    }
}
