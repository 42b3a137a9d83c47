//! Hole diameter at any measured depth: by section (top down) or from a caliper log.

/// One hole section: the hole has `diameter_m` from the previous section's end down to `to_md_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoleSection {
    /// Bottom of the section, m MD.
    pub to_md_m: f64,
    /// Hole diameter, m.
    pub diameter_m: f64,
    /// Wall friction coefficient in this section, if given (else the operation's).
    pub friction: Option<f64>,
}

/// Hole size along the well: sections top down, optionally overridden by a caliper log
/// (linear interpolation between caliper points, sections outside the caliper's MD range).
#[derive(Debug, Clone, PartialEq)]
pub struct HoleSize {
    sections: Vec<HoleSection>,
    caliper: Vec<(f64, f64)>,
}

impl HoleSize {
    /// Hole of `sections` (non-empty, `to_md_m` strictly increasing, diameters positive:
    /// the case reader validates) and an optional caliper `(md_m, diameter_m)` list sorted by MD.
    pub fn new(sections: Vec<HoleSection>, caliper: Vec<(f64, f64)>) -> HoleSize {
        HoleSize { sections, caliper }
    }

    /// A hole of one diameter everywhere.
    pub fn uniform(diameter_m: f64) -> HoleSize {
        HoleSize::new(
            vec![HoleSection {
                to_md_m: f64::INFINITY,
                diameter_m,
                friction: None,
            }],
            vec![],
        )
    }

    /// The sections, top down.
    pub fn sections(&self) -> &[HoleSection] {
        &self.sections
    }

    /// The caliper points `(md_m, diameter_m)` sorted by MD (empty without a caliper).
    pub fn caliper(&self) -> &[(f64, f64)] {
        &self.caliper
    }

    fn section_at(&self, md_m: f64) -> &HoleSection {
        self.sections
            .iter()
            .find(|s| md_m <= s.to_md_m + 1e-9)
            .unwrap_or_else(|| self.sections.last().expect("at least one hole section"))
    }

    /// Hole diameter at `md_m`, m. Below the deepest section the last diameter continues.
    pub fn diameter_at(&self, md_m: f64) -> f64 {
        if self.caliper.len() >= 2 && md_m >= self.caliper[0].0 && md_m <= self.caliper[self.caliper.len() - 1].0 {
            let k = self
                .caliper
                .partition_point(|&(m, _)| m <= md_m)
                .clamp(1, self.caliper.len() - 1);
            let (m0, d0) = self.caliper[k - 1];
            let (m1, d1) = self.caliper[k];
            let lam = if m1 > m0 { (md_m - m0) / (m1 - m0) } else { 0.0 };
            return d0 + lam * (d1 - d0);
        }
        self.section_at(md_m).diameter_m
    }

    /// Friction coefficient given for the section holding `md_m`, if any.
    pub fn friction_at(&self, md_m: f64) -> Option<f64> {
        self.section_at(md_m).friction
    }

    /// Deepest MD covered by a section, m.
    pub fn deepest_md(&self) -> f64 {
        self.sections.last().map(|s| s.to_md_m).unwrap_or(0.0)
    }

    /// Bottom of the hole drilled by larger bits than one of `bit_od_m`, m MD: the end of the run
    /// of sections from the top that are more than [`PREVIOUS_HOLE_MARGIN_M`] wider than the bit
    /// (the cased or earlier hole sections); `None` when the top section is not. A wide section
    /// below bit-size hole is a washout, not earlier hole, and does not count.
    pub fn previous_hole_bottom_md(&self, bit_od_m: f64) -> Option<f64> {
        self.sections
            .iter()
            .take_while(|s| s.diameter_m > bit_od_m + PREVIOUS_HOLE_MARGIN_M)
            .last()
            .map(|s| s.to_md_m)
    }
}

/// A hole section this much wider than the bit (1 in) was drilled by a larger bit, m.
pub const PREVIOUS_HOLE_MARGIN_M: f64 = 0.0254;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_and_caliper() {
        let h = HoleSize::new(
            vec![
                HoleSection {
                    to_md_m: 1000.0,
                    diameter_m: 0.311,
                    friction: Some(0.2),
                },
                HoleSection {
                    to_md_m: 3000.0,
                    diameter_m: 0.216,
                    friction: None,
                },
            ],
            vec![(1500.0, 0.25), (1600.0, 0.23)],
        );
        assert_eq!(h.diameter_at(10.0), 0.311);
        assert_eq!(h.diameter_at(1000.0), 0.311);
        assert_eq!(h.diameter_at(1000.5), 0.216);
        assert!((h.diameter_at(1550.0) - 0.24).abs() < 1e-12);
        assert_eq!(h.diameter_at(4000.0), 0.216);
        assert_eq!(h.friction_at(500.0), Some(0.2));
        assert_eq!(h.friction_at(2000.0), None);
        // reference: the 12.25 in (0.311 m) section ends at 1000 m above 8.5 in (0.216 m) hole
        assert_eq!(h.previous_hole_bottom_md(0.216), Some(1000.0));
        // a 12.25 in bit drilled all of it; a washout below bit-size hole is not earlier hole
        assert_eq!(h.previous_hole_bottom_md(0.311), None);
        let washout = |d: f64| HoleSection {
            to_md_m: 0.0,
            diameter_m: d,
            friction: None,
        };
        let mut sections = vec![washout(0.216), washout(0.35), washout(0.216)];
        for (k, s) in sections.iter_mut().enumerate() {
            s.to_md_m = 100.0 * (k + 1) as f64;
        }
        assert_eq!(HoleSize::new(sections, vec![]).previous_hole_bottom_md(0.216), None);
    }
}
