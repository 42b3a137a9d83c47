//! The `survey` command's CSV: `md_m,inc_deg,azi_deg,tvd_m,north_m,east_m,dls_deg_per_30m`.

use super::num;
use crate::geometry::WellPath;

/// Header of the survey table (docs/guide.md).
pub const HEADER: &str = "md_m,inc_deg,azi_deg,tvd_m,north_m,east_m,dls_deg_per_30m";

/// One row per station: minimum-curvature positions and the DLS of the interval ending there.
pub fn survey_csv(path: &WellPath) -> Result<String, String> {
    let mut out = String::from(HEADER);
    out.push('\n');
    for (k, s) in path.stations().iter().enumerate() {
        let p = path.station_position(k);
        let dls = path.dls_before(k).to_degrees() * 30.0;
        out.push_str(&format!(
            "{},{},{},{},{},{},{}\n",
            num(s.md_m, 3)?,
            num(s.inc_rad.to_degrees(), 4)?,
            num(crate::geometry::survey::degrees_in_turn(s.azi_rad.to_degrees(), 4), 4)?,
            num(p.z, 4)?,
            num(p.x, 4)?,
            num(p.y, 4)?,
            num(dls, 4)?
        ));
    }
    Ok(out)
}
