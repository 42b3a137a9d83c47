//! `--witsml FILE` of `predict` and `backanalyze`: the predicted path as a WITSML 1.4.1.1
//! `trajectory` (docs/guide.md, "WITSML out"). The first station is the tie-in (where the
//! prediction starts, on the measured hole), typed `tie in point`; every predicted station is
//! typed `N E and TVD` ("a point on a computed trajectory") with `typeSurveyTool` `drillpath
//! prediction`, so that a reader (drillpath's included) never takes it for a measurement.
//! Units are declared on every measure (`m`, `dega`); values are written with the digits of
//! `trajectory.csv` (MD 3 decimals, angles 4, positions 3), so reading the file back gives the
//! same stations to the printed digits.

use std::fmt::Write;

use super::num;
use crate::case::{AzimuthReference, SurveyFile};
use crate::geometry::Vec3;

/// One station of the written trajectory, SI.
#[derive(Debug, Clone, Copy)]
pub struct OutStation {
    /// MD, m.
    pub md_m: f64,
    /// Inclination, rad.
    pub inc_rad: f64,
    /// Azimuth, rad.
    pub azi_rad: f64,
    /// Position (north, east, tvd), m.
    pub position: Vec3,
}

/// One trajectory object to write: its name and stations (the first is the tie-in).
#[derive(Debug, Clone)]
pub struct OutTrajectory<'a> {
    /// The trajectory's name (the case's name and what was predicted).
    pub name: String,
    /// The stations, in increasing MD; one whose printed MD repeats the previous one is left out.
    pub stations: Vec<OutStation>,
    /// The survey file of the case (its north, declination and convergence are written).
    pub survey: &'a SurveyFile,
}

/// `&`, `<`, `>`, `"` escaped for XML text and attributes.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The WITSML file holding `trajectories` (one per case).
pub fn trajectories_xml(trajectories: &[OutTrajectory]) -> Result<String, String> {
    let mut x = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<trajectorys xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n",
    );
    for (k, t) in trajectories.iter().enumerate() {
        trajectory(&mut x, k + 1, t)?;
    }
    x.push_str("</trajectorys>\n");
    Ok(x)
}

fn trajectory(x: &mut String, k: usize, t: &OutTrajectory) -> Result<(), String> {
    let name = escape(&t.name);
    let _ = writeln!(
        x,
        "<trajectory uidWell=\"drillpath\" uidWellbore=\"drillpath\" uid=\"drillpath-prediction-{k}\">\n<nameWell>{name}</nameWell>\n<nameWellbore>{name}</nameWellbore>\n<name>{name}: drillpath prediction</name>"
    );
    let s = t.survey;
    if let Some(d) = s.magnetic_declination_rad {
        let _ = writeln!(x, "<magDeclUsed uom=\"dega\">{}</magDeclUsed>", num(d.to_degrees(), 6)?);
    }
    if let Some(c) = s.grid_convergence_rad {
        let _ = writeln!(x, "<gridCorUsed uom=\"dega\">{}</gridCorUsed>", num(c.to_degrees(), 6)?);
    }
    let _ = writeln!(x, "<definitive>false</definitive>");
    match s.azimuth_reference {
        AzimuthReference::Unspecified => {
            let _ = writeln!(
                x,
                "<!-- the case's survey does not state the north of its azimuths: no aziRef -->"
            );
        }
        r => {
            let _ = writeln!(x, "<aziRef>{}</aziRef>", r.describe());
        }
    }
    let mut last_md = String::new();
    let mut first = true;
    for st in &t.stations {
        let md = num(st.md_m, 3)?;
        if md == last_md {
            continue;
        }
        let (kind, tool) = if first {
            ("tie in point", "")
        } else {
            ("N E and TVD", "<typeSurveyTool>drillpath prediction</typeSurveyTool>")
        };
        let p = &st.position;
        let _ = writeln!(
            x,
            "<trajectoryStation uid=\"P-{md}\"><typeTrajStation>{kind}</typeTrajStation>{tool}<md uom=\"m\">{md}</md><tvd uom=\"m\">{}</tvd><incl uom=\"dega\">{}</incl><azi uom=\"dega\">{}</azi><dispNs uom=\"m\">{}</dispNs><dispEw uom=\"m\">{}</dispEw></trajectoryStation>",
            num(p.z, 3)?,
            num(st.inc_rad.to_degrees(), 4)?,
            num(crate::geometry::survey::degrees_in_turn(st.azi_rad.to_degrees(), 4), 4)?,
            num(p.x, 3)?,
            num(p.y, 3)?,
        );
        last_md = md;
        first = false;
    }
    x.push_str("</trajectory>\n");
    Ok(())
}
