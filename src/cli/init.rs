//! `drillpath init`: write a commented starter case and its survey CSV for a user to edit.

use super::outputs::Outputs;
use anyhow::bail;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Name of the survey file written next to the case.
pub const SURVEY_FILE: &str = "survey.csv";

/// The starter case text (references `survey.csv` in the same directory).
pub const STARTER_CASE: &str = r#"# drillpath starter case, written by `drillpath init`. Edit it for your well.
# Every quantity is a number in the field's default unit or a string with units ("8.5 in",
# "1.2 sg", "30 ft"). Run:  drillpath solve case.toml   and   drillpath predict case.toml --ahead 30m
# ASSUMED values throughout: a synthetic build-and-hold well and a typical 8.5 in rotary BHA.

name = "Starter case"
description = "Synthetic well: vertical to 300 m, build 3 deg/30 m to 30 deg, hold to 1000 m"

[well]
survey = "survey.csv"          # columns md_m, inc_deg, azi_deg (units in the header, e.g. md_ft)
hole = [
  { to_md = "300 m", diameter = "12.25 in", friction = 0.2 },   # cased hole above the shoe
  { to_md = "1000 m", diameter = "8.5 in" },                   # open hole: [operation] friction
]

[mud]
density = "1.2 sg"             # same mud inside and outside the string
plastic_viscosity = "20 cP"    # mud drag torque on the rotating string

[operation]
mode = "drilling"              # drilling, sliding, rotating_off_bottom, trip_in, trip_out
bit_md = "1000 m"              # bit depth; the survey must reach it
wob = "100 kN"                 # weight on bit
rpm = 80                       # surface rotary speed, rev/min
rop = "15 m/h"                 # rate of penetration
friction = 0.25                # wall friction factor (open hole)

# The string from the bit upward. A component without `length` fills the string to surface.
[[string]]
type = "bit"
name = "8.5 in PDC bit"
od = "8.5 in"
length = "0.3 m"

[[string]]
type = "stabilizer"
name = "near-bit stabilizer, full gauge"
od = "8.5 in"                  # blade OD (touches the wall)
body_od = "6.5 in"
id = "2.8125 in"
length = "1.6 m"
blade_length = "0.4 m"         # blades' length, used with [solver] stabilizer_contact = "blade" (default: a quarter of length)

[[string]]
type = "collar"
name = "6.5 in drill collars"
od = "6.5 in"
id = "2.8125 in"
length = "18.3 m"

[[string]]
type = "stabilizer"
name = "string stabilizer"
od = "8.4375 in"
body_od = "6.5 in"
id = "2.8125 in"
length = "1.6 m"

[[string]]
type = "collar"
name = "6.5 in drill collars"
od = "6.5 in"
id = "2.8125 in"
length = "55 m"

[[string]]
type = "hwdp"
name = "5 in HWDP"
od = "5 in"
id = "3 in"
length = "110 m"
weight = "49.3 lb/ft"          # adjusted weight including tool joints
tool_joint_od = "6.5 in"
joint_length = "30 ft"

[[string]]
type = "pipe"
name = "5 in 19.5 lb/ft S-135 drill pipe"
od = "5 in"
id = "4.276 in"
weight = "33.6 kg/m"           # adjusted weight including tool joints
tool_joint_od = "6.625 in"
joint_length = "30 ft"
grade = "S-135"
# no length: fills the string to surface

[bit_rock]
law = "ho"                     # bit-rock interaction law for `drillpath predict`
lateral_drillability = 1.0     # lateral/axial drillability ratio, (0, 1]
rock_anisotropy = 0.0          # rock anisotropy index
step = "1 m"                   # prediction step

[solver]
element_length = "1 m"         # longest element in the pipe
bha_element_length = "0.5 m"   # longest element in the BHA
tolerance = 1e-4               # contact gap tolerance relative to the clearance
fidelity = "auto"
method = "newton"
stabilizer_contact = "point"   # "blade": stabilizers touch along their blades (docs/guide.md)
"#;

/// Survey stations of the starter well: (MD m, inclination deg, azimuth deg).
pub fn starter_stations() -> Vec<(f64, f64, f64)> {
    let mut v = Vec::new();
    let azi = 60.0;
    let mut md: f64 = 0.0;
    while md <= 1000.0 + 1e-9 {
        let inc = if md <= 300.0 {
            0.0
        } else {
            ((md - 300.0) / 30.0 * 3.0).min(30.0)
        };
        v.push((md, inc, azi));
        md += 30.0;
    }
    if (v.last().map(|s| s.0).unwrap_or(0.0) - 1000.0).abs() > 1e-9 {
        v.push((1000.0, 30.0, azi));
    }
    v
}

/// The starter survey CSV text.
pub fn starter_survey() -> String {
    let mut s = String::from(
        "# drillpath starter survey (SYNTHETIC): vertical to 300 m, build 3 deg/30 m at azimuth 60 deg to 30 deg, hold\nmd_m,inc_deg,azi_deg\n",
    );
    for (md, inc, azi) in starter_stations() {
        s.push_str(&format!("{md:.1},{inc:.2},{azi:.2}\n"));
    }
    s
}

/// Write the starter case to `case` and `survey.csv` next to it;
/// refuses to overwrite either unless `force`.
pub fn run(case: PathBuf, force: bool) -> anyhow::Result<()> {
    let dir = case
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let survey = dir.join(SURVEY_FILE);
    let mut outputs = Outputs::new();
    for p in [&case, &survey] {
        if p.exists() && !force {
            bail!("{} exists; not overwritten (use --force)", p.display());
        }
        outputs.file("FILE", p)?;
    }
    outputs.stage(survey.clone(), starter_survey());
    outputs.stage(case.clone(), STARTER_CASE);
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "wrote {} and {}", case.display(), survey.display())?;
    writeln!(out, "next: drillpath solve {}", case.display())?;
    Ok(())
}
