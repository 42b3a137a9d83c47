//! Generates the known-truth wells of `wells/known-truth/`: wells drilled by the model itself,
//! so that the tracking tests know what the predictor is not told.
//!
//! Each well starts from a given kick-off (vertical to 150 m, 3 deg/30 m to 20 deg at 350 m)
//! and is drilled in three BHA runs of 240 m: a fulcrum assembly builds, a packed one holds,
//! a pendulum drops. The truth is the stiff **whole string** with a finer mesh than the
//! predictor's (0.25 m in the BHA, 1 m along the pipe), 1 m steps, and a hidden tendency:
//!
//! - `none`: no hidden tendency (the control);
//! - `walk`: a constant walk, a turn of the hole of 1.5 deg/30 m to the right beyond what the
//!   assemblies drill (`MarchSettings::tendency`);
//! - `anisotropy`: a formation anisotropy `I_r = 0.2` of bedding dipping 15 deg toward north; the
//!   predictor is told the bedding but not the anisotropy (its cases estimate it);
//! - `change`: a build tendency of 1.5 deg/30 m that starts half way through the packed run.
//!
//! The survey is the true hole sampled every 30 m with survey noise (inclination 0.1 deg,
//! azimuth 0.4 deg, one standard deviation, a fixed seed: the noise `[tracking]` assumes by
//! default). Each folder gets the noisy `survey.csv`, the predictor's cases
//! `run1.toml`..`run3.toml` (default mesh, no hidden tendency), and `truth.toml`: the hidden
//! parameters, their net effect on each run (the turn per metre of the run with the tendency
//! less that of the `none` well), and for the wells with a hidden tendency its effect on each
//! 30 m survey interval (`[[interval]]`: the true turn less the truth model's own prediction
//! without the tendency from the true hole at the interval's start, toward the high side and
//! the right): what an assimilation must recover there.
//!
//! Run: `cargo run --release --example known_truth -- wells/known-truth` (about 5 minutes).

use drillpath::case::Case;
use drillpath::geometry::frame::Frame;
use drillpath::geometry::{Station, Survey, Vec3, WellPath};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::predict::intervals::{predict_interval_path, Interval, RunModel};
use drillpath::predict::law::deviation;
use drillpath::predict::march::{predict_from, MarchSettings, Tendency};
use drillpath::predict::tracking::assimilate::turn_between;
use drillpath::predict::tracking::references::Direction;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Run ends, m MD.
const RUN_ENDS: [f64; 3] = [590.0, 830.0, 1070.0];
/// Start of the first run, m MD.
const START_MD: f64 = 350.0;
/// Survey spacing, m.
const SPACING: f64 = 30.0;
/// Survey noise, deg.
const INC_NOISE_DEG: f64 = 0.1;
/// Survey noise, deg (the assumed noise of `[tracking]`'s defaults: typical MWD accuracy).
const AZI_NOISE_DEG: f64 = 0.4;
/// Hidden tendency, deg/30 m.
const HIDDEN_DEG_PER_30M: f64 = 1.5;
/// Hidden anisotropy.
const HIDDEN_ANISOTROPY: f64 = 0.2;

const BIT: &str = "[[string]]\ntype = \"bit\"\nod = \"8.5 in\"\nlength = \"0.3 m\"\n";

fn stab() -> String {
    "[[string]]\ntype = \"stabilizer\"\nod = \"8.5 in\"\nbody_od = \"6.5 in\"\nid = \"2.8125 in\"\nlength = \"1.5 m\"\n"
        .into()
}

fn collar(len: &str) -> String {
    format!("[[string]]\ntype = \"collar\"\nod = \"6.5 in\"\nid = \"2.8125 in\"\nlength = \"{len}\"\n")
}

const PIPE: &str = "[[string]]\ntype = \"pipe\"\nname = \"5 in drill pipe\"\nod = \"5 in\"\nid = \"4.276 in\"\nweight = \"29 kg/m\"\ntool_joint_od = \"6.625 in\"\n";

/// The three runs: name, BHA, WOB kN.
fn runs() -> [(&'static str, String, f64); 3] {
    [
        ("fulcrum", format!("{BIT}{}{}", stab(), collar("120 m")), 100.0),
        (
            "packed",
            format!(
                "{BIT}{}{}{}{}{}{}",
                stab(),
                collar("3 m"),
                stab(),
                collar("8.5 m"),
                stab(),
                collar("105 m")
            ),
            90.0,
        ),
        (
            "pendulum",
            format!("{BIT}{}{}{}", collar("18 m"), stab(), collar("100 m")),
            80.0,
        ),
    ]
}

/// The case text of run `k` (`truth`: the truth's finer mesh and its law).
fn case_text(k: usize, variant: &str, truth: bool) -> String {
    let (name, bha, wob) = &runs()[k];
    let anis = if variant == "anisotropy" {
        let ir = if truth { HIDDEN_ANISOTROPY } else { 0.0 };
        format!("rock_anisotropy = {ir}\ndip = \"15 deg\"\ndip_direction = \"0 deg\"\n")
    } else {
        String::new()
    };
    // the wells were drilled, and are modelled, with point stabilizers (the model before
    // issue 20's blades; the runs must use the model that drilled them)
    let solver = if truth {
        "[solver]\nelement_length = \"1 m\"\nbha_element_length = \"0.25 m\"\nstabilizer_contact = \"point\"\n"
    } else {
        "[solver]\n# drilled by the model with point stabilizers (examples/known_truth.rs)\nstabilizer_contact = \"point\"\n"
    };
    let tracking = if variant == "anisotropy" && !truth {
        "[tracking]\nestimate = [\"rock_anisotropy\"]\n"
    } else {
        ""
    };
    format!(
        "# known-truth well `{variant}`, run {} of 3: {name} assembly (generated by examples/known_truth.rs)\nname = \"known truth {variant}: run {} ({name})\"\n\n[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"1200 m\", diameter = \"8.5 in\" }}]\n\n[mud]\ndensity = \"1.2 sg\"\n\n[operation]\nmode = \"drilling\"\nbit_md = \"{} m\"\nwob = \"{wob} kN\"\nrpm = 80\nrop = \"15 m/h\"\nfriction = 0.25\n\n{bha}{PIPE}\n[bit_rock]\nstep = \"1 m\"\n{anis}\n{solver}{tracking}",
        k + 1,
        k + 1,
        RUN_ENDS[k]
    )
}

/// The kick-off: vertical to 150 m, 3 deg/30 m to 20 deg at 350 m, azimuth 40 deg.
fn kick_off() -> Vec<Station> {
    (0..=(START_MD / 10.0) as usize)
        .map(|k| {
            let md = 10.0 * k as f64;
            let inc = ((md - 150.0).max(0.0) * 3.0 / 30.0).min(20.0);
            Station::from_deg(md, inc, 40.0)
        })
        .collect()
}

fn path_of(stations: &[Station]) -> WellPath {
    WellPath::new(&Survey::new(stations.to_vec()).expect("stations"), Vec3::zeros()).expect("path")
}

/// A fixed-seed normal sampler (xorshift64* and Box-Muller).
struct Noise(u64);

impl Noise {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545F4914F6CDD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (a, b) = (self.uniform(), self.uniform());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// The true hole of `variant` (noise-free stations every metre from the kick-off's end), with
/// the truth cases written to `dir` first (loaded from there).
fn drill(dir: &Path, variant: &str) -> Vec<Station> {
    let mut stations = kick_off();
    // the truth cases need a survey to be read: the kick-off continued straight to TD
    let mut draft = String::from("md_m,inc_deg,azi_deg\n");
    for s in &stations {
        writeln!(
            draft,
            "{},{},{}",
            s.md_m,
            s.inc_rad.to_degrees(),
            s.azi_rad.to_degrees()
        )
        .unwrap();
    }
    writeln!(draft, "1200,20,40").unwrap();
    let scratch = dir.join("truth-scratch");
    std::fs::create_dir_all(&scratch).unwrap();
    std::fs::write(scratch.join("survey.csv"), draft).unwrap();
    for (k, &run_end) in RUN_ENDS.iter().enumerate() {
        let file = scratch.join(format!("run{}.toml", k + 1));
        std::fs::write(&file, case_text(k, variant, true)).unwrap();
        let case: Case = load_case(&file, &CaseOverrides::default()).expect("truth case");
        let from = stations.last().unwrap().md_m;
        let mut settings = MarchSettings::from_case(&case);
        settings.cut_m = Some(case.string.length_m());
        // the hidden tendency, per part of the run
        let half = from + (run_end - from) / 2.0;
        let k30 = HIDDEN_DEG_PER_30M.to_radians() / 30.0;
        let parts: Vec<(f64, Tendency)> = match variant {
            "walk" => vec![(
                run_end,
                Tendency {
                    build_rad_per_m: 0.0,
                    right_rad_per_m: k30,
                },
            )],
            "change" if k == 1 => vec![
                (half, Tendency::default()),
                (
                    run_end,
                    Tendency {
                        build_rad_per_m: k30,
                        right_rad_per_m: 0.0,
                    },
                ),
            ],
            "change" if k == 2 => vec![(
                run_end,
                Tendency {
                    build_rad_per_m: k30,
                    right_rad_per_m: 0.0,
                },
            )],
            _ => vec![(run_end, Tendency::default())],
        };
        for (to, tendency) in parts {
            settings.tendency = tendency;
            let start = path_of(&stations);
            let p = predict_from(&case, &case.bit_rock, &start, to, &settings, &mut None, &mut |_| {})
                .unwrap_or_else(|e| panic!("{variant} run {}: {e}", k + 1));
            let from = stations.last().unwrap().md_m;
            let n = (to - from).round() as usize;
            for i in 1..=n {
                let md = from + (to - from) * i as f64 / n as f64;
                let q = p.path.point_at(md);
                stations.push(Station {
                    md_m: md,
                    inc_rad: q.inc_rad,
                    azi_rad: q.azi_rad,
                });
            }
        }
        eprintln!("{variant}: run {} drilled to {} m", k + 1, run_end);
    }
    std::fs::remove_dir_all(&scratch).ok();
    stations
}

/// The truth cases of `variant` reading the true hole `stations` from `dir/truth-scratch`.
fn truth_cases(dir: &Path, variant: &str, stations: &[Station]) -> Vec<Case> {
    let scratch = dir.join("truth-scratch");
    std::fs::create_dir_all(&scratch).unwrap();
    let mut csv = String::from("md_m,inc_deg,azi_deg\n");
    for s in stations {
        writeln!(csv, "{},{},{}", s.md_m, s.inc_rad.to_degrees(), s.azi_rad.to_degrees()).unwrap();
    }
    std::fs::write(scratch.join("survey.csv"), csv).unwrap();
    let cases = (0..3)
        .map(|k| {
            let file = scratch.join(format!("run{}.toml", k + 1));
            std::fs::write(&file, case_text(k, variant, true)).unwrap();
            load_case(&file, &CaseOverrides::default()).expect("truth case")
        })
        .collect();
    std::fs::remove_dir_all(&scratch).ok();
    cases
}

/// The hidden tendency's effect on each survey interval (from, to, turn toward the high side
/// and the right, rad): the true turn less the truth model's prediction without it from the
/// true hole at the interval's start.
fn hidden_per_interval(
    dir: &Path,
    variant: &str,
    stations: &[Station],
    survey_mds: &[f64],
) -> Vec<(f64, f64, [f64; 2])> {
    let cases = truth_cases(dir, variant, stations);
    let settings: Vec<MarchSettings> = cases
        .iter()
        .map(|c| MarchSettings {
            cut_m: Some(c.string.length_m()),
            ..MarchSettings::from_case(c)
        })
        .collect();
    let runs: Vec<RunModel> = cases.iter().zip(&settings).map(|(c, s)| RunModel::of(c, s)).collect();
    let path = path_of(stations);
    let dir_at = |p: &WellPath, md: f64| {
        let q = p.point_at(md);
        Direction {
            inc_rad: q.inc_rad,
            azi_rad: q.azi_rad,
        }
    };
    let mds: Vec<f64> = survey_mds.iter().copied().filter(|&m| m >= START_MD).collect();
    mds.windows(2)
        .map(|w| {
            let iv = Interval {
                from_md_m: w[0],
                to_md_m: w[1],
                measured: (0.0, 0.0),
            };
            let p = predict_interval_path(&runs, &iv, &mut None).expect("truth interval");
            (w[0], w[1], turn_between(&dir_at(&p.path, w[1]), &dir_at(&path, w[1])))
        })
        .collect()
}

/// The turn (toward the high side, toward the right) per metre of each run of `stations`.
fn run_turns(stations: &[Station]) -> Vec<[f64; 2]> {
    let path = path_of(stations);
    let mut out = Vec::new();
    let mut from = START_MD;
    for &to in &RUN_ENDS {
        let a = path.point_at(from);
        let b = path.point_at(to);
        let (h, r) = deviation(&Frame::from_tangent(&a.tangent, a.azi_rad), &b.tangent);
        out.push([h / (to - from), r / (to - from)]);
        from = to;
    }
    out
}

fn main() {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "wells/known-truth".into()));
    let mut control: Option<Vec<[f64; 2]>> = None;
    for variant in ["none", "walk", "anisotropy", "change"] {
        let dir = out.join(variant);
        std::fs::create_dir_all(&dir).unwrap();
        let truth = drill(&dir, variant);
        let turns = run_turns(&truth);
        let control_turns = control.get_or_insert_with(|| turns.clone()).clone();
        // the survey: the true hole every 30 m, with noise
        let mut noise = Noise(0x9E37_79B9_7F4A_7C15 ^ variant.len() as u64);
        let mut survey_mds = Vec::new();
        let mut csv = format!(
            "# known-truth well `{variant}` (examples/known_truth.rs): the true hole every {SPACING} m with survey noise {INC_NOISE_DEG} deg (inclination), {AZI_NOISE_DEG} deg (azimuth)\nmd [m],inc [deg],azi [deg]\n"
        );
        let path = path_of(&truth);
        let n = (RUN_ENDS[2] / SPACING).floor() as usize;
        for k in 0..=n {
            let md = SPACING * k as f64;
            let p = path.point_at(md);
            let (inc, azi) = if md <= START_MD {
                (p.inc_rad.to_degrees(), p.azi_rad.to_degrees())
            } else {
                (
                    p.inc_rad.to_degrees() + INC_NOISE_DEG * noise.normal(),
                    p.azi_rad.to_degrees() + AZI_NOISE_DEG * noise.normal(),
                )
            };
            writeln!(csv, "{md},{inc:.4},{:.4}", azi.rem_euclid(360.0)).unwrap();
            survey_mds.push(md);
        }
        if (RUN_ENDS[2] - SPACING * n as f64).abs() > 1e-9 {
            let p = path.point_at(RUN_ENDS[2]);
            writeln!(
                csv,
                "{},{:.4},{:.4}",
                RUN_ENDS[2],
                p.inc_rad.to_degrees() + INC_NOISE_DEG * noise.normal(),
                (p.azi_rad.to_degrees() + AZI_NOISE_DEG * noise.normal()).rem_euclid(360.0)
            )
            .unwrap();
            survey_mds.push(RUN_ENDS[2]);
        }
        std::fs::write(dir.join("survey.csv"), csv).unwrap();
        for k in 0..3 {
            std::fs::write(dir.join(format!("run{}.toml", k + 1)), case_text(k, variant, false)).unwrap();
        }
        let mut t = format!("# the hidden truth of the known-truth well `{variant}` (examples/known_truth.rs)\nvariant = \"{variant}\"\n");
        let per30 = |x: f64| (x * 30.0).to_degrees();
        for (k, (w, c)) in turns.iter().zip(&control_turns).enumerate() {
            writeln!(
                t,
                "[[run]]\nrun = {}\nturn_deg_per_30m = [{:.5}, {:.5}]\nnet_hidden_deg_per_30m = [{:.5}, {:.5}]",
                k + 1,
                per30(w[0]),
                per30(w[1]),
                per30(w[0] - c[0]),
                per30(w[1] - c[1])
            )
            .unwrap();
        }
        writeln!(
            t,
            "[hidden]\ntendency_deg_per_30m = {}\nrock_anisotropy = {}",
            if matches!(variant, "walk" | "change") {
                HIDDEN_DEG_PER_30M
            } else {
                0.0
            },
            if variant == "anisotropy" {
                HIDDEN_ANISOTROPY
            } else {
                0.0
            }
        )
        .unwrap();
        if matches!(variant, "walk" | "change") {
            for (from, to, h) in hidden_per_interval(&dir, variant, &truth, &survey_mds) {
                writeln!(
                    t,
                    "[[interval]]\nfrom = {from}\nto = {to}\nhidden_turn_deg = [{:.5}, {:.5}]",
                    h[0].to_degrees(),
                    h[1].to_degrees()
                )
                .unwrap();
            }
        }
        std::fs::write(dir.join("truth.toml"), t).unwrap();
        eprintln!(
            "{variant}: turns per run {:?}",
            turns.iter().map(|x| [per30(x[0]), per30(x[1])]).collect::<Vec<_>>()
        );
    }
}
