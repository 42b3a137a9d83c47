//! What the commands print on stdout and stderr, through the built binary: `--units` on the
//! readable summaries (solve at two fidelity levels, predict, backanalyze, loads), no negative
//! zero, a clean exit into a closed pipe, and the progress bar (silent into a pipe or with -q,
//! drawn on a terminal).
//!
//! Reference for the units: exact definitions, 1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N
//! (1 klbf = 4.4482216 kN, 1 ft.lbf = 1.3558179 N.m); the same run printed in SI and oilfield
//! must agree to the rounding of the printed digits (half a unit of the last digit of each).

use std::io::Read;
use std::process::{Command, Stdio};

use crate::common::{drillpath, example_case, root, run_in, run_ok, Run};

const FT: f64 = 0.3048;
const KLBF_KN: f64 = 4.448_221_615_260_5;
const FTLBF_KNM: f64 = 4.448_221_615_260_5 * 0.3048 / 1e3;

/// The case file of example well `name`, as a command-line argument.
fn well(name: &str) -> String {
    example_case(name).to_string_lossy().into_owned()
}

/// `drillpath args` in the package root; it must succeed.
fn run(args: &[&str]) -> Run {
    run_ok(root(), args)
}

/// stdout of `args` with `--units si` and `--units oilfield`; both checked for units of the
/// other system and for negative zeros, and stderr empty (no progress into a pipe).
fn both(args: &[&str]) -> (String, String) {
    let mut texts = Vec::new();
    for units in ["si", "oilfield"] {
        let mut a = args.to_vec();
        a.extend(["--units", units]);
        let out = run(&a);
        assert!(out.stderr.is_empty(), "stderr not empty into a pipe: {}", out.stderr);
        let text = out.stdout;
        let foreign: &[&str] = if units == "si" {
            // (not "in": case names say "8.5 in section")
            &["ft", "klbf", "ft.lbf", "ksi"]
        } else {
            &["m", "kN", "kN.m", "MPa", "mm"]
        };
        for u in foreign {
            assert!(unit_uses(&text, u) == 0, "{units} output shows a value in {u}:\n{text}");
        }
        assert_no_negative_zero(&text);
        texts.push(text);
    }
    let oil = texts.pop().unwrap();
    (texts.pop().unwrap(), oil)
}

/// Number of places where a number is followed by ` unit` and a non-letter.
fn unit_uses(text: &str, unit: &str) -> usize {
    let pat = format!(" {unit}");
    text.match_indices(&pat)
        .filter(|(i, _)| text[..*i].chars().last().is_some_and(|c| c.is_ascii_digit()))
        .filter(|(i, _)| {
            text[i + pat.len()..]
                .chars()
                .next()
                .is_none_or(|c| !c.is_ascii_alphanumeric() && c != '.')
        })
        .count()
}

/// No printed number is a negative zero ("-0", "-0.0", "-0.000").
fn assert_no_negative_zero(text: &str) {
    for (i, _) in text.match_indices("-0") {
        let rest: String = text[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        assert!(
            !rest.chars().all(|c| c == '0' || c == '.'),
            "negative zero `-{rest}` in:\n{text}"
        );
    }
}

/// The first line of `text` starting with `start` (after indentation) or, if none, containing it.
fn line<'a>(text: &'a str, start: &str) -> &'a str {
    text.lines()
        .find(|l| l.trim_start().starts_with(start))
        .or_else(|| text.lines().find(|l| l.contains(start)))
        .unwrap_or_else(|| panic!("no line `{start}` in:\n{text}"))
}

/// The number after the first `label` in `l` that is followed by a number, with its unit word.
fn after(l: &str, label: &str) -> (f64, String) {
    for (i, _) in l.match_indices(label) {
        let rest = &l[i + label.len()..];
        let n: String = rest
            .chars()
            .take_while(|c| c.is_ascii_digit() || "+-.e".contains(*c))
            .collect();
        if let Ok(v) = n.parse::<f64>() {
            let unit: String = rest[n.len()..]
                .trim_start()
                .chars()
                .take_while(|c| !" ,;)\n".contains(*c))
                .collect();
            return (v, unit);
        }
    }
    panic!("no number after `{label}` in `{l}`")
}

/// Decimals printed in `v`'s text form are not kept by f64; the tolerance is half a unit of
/// `last_si` and `last_oil` (the last printed digit in each system) converted to SI.
fn agree(si: (f64, String), oil: (f64, String), units: (&str, &str), factor: f64, last: (f64, f64)) {
    assert_eq!((si.1.as_str(), oil.1.as_str()), units, "units");
    let tol = 0.5 * last.0 + 0.5 * last.1 * factor + 1e-9;
    assert!(
        (oil.0 * factor - si.0).abs() <= tol,
        "{} {} vs {} {} (x {factor}): differ by more than {tol}",
        si.0,
        units.0,
        oil.0,
        units.1
    );
}

#[test]
fn solve_prints_the_same_numbers_in_si_and_oilfield() {
    let case = well("j-shape");
    let (si, oil) = both(&["solve", &case, "--bit-md", "1500 m"]);
    let (ls, lo) = (line(&si, "mode "), line(&oil, "mode "));
    agree(
        after(ls, "bit at "),
        after(lo, "bit at "),
        ("m", "ft"),
        FT,
        (0.01, 0.01),
    );
    agree(
        after(ls, "WOB "),
        after(lo, "WOB "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.1, 0.1),
    );
    let (ls, lo) = (line(&si, "bit:"), line(&oil, "bit:"));
    agree(
        after(ls, "build force "),
        after(lo, "build force "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.001, 0.001),
    );
    agree(
        after(ls, "torque "),
        after(lo, "torque "),
        ("kN.m", "ft.lbf"),
        FTLBF_KNM,
        (0.01, 1.0),
    );
    let (ls, lo) = (line(&si, "surface:"), line(&oil, "surface:"));
    agree(
        after(ls, "hook load "),
        after(lo, "hook load "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.1, 0.1),
    );
    agree(
        after(ls, "torque "),
        after(lo, "torque "),
        ("kN.m", "ft.lbf"),
        FTLBF_KNM,
        (0.01, 1.0),
    );
    // a surface torque of kN.m size is thousands of ft.lbf (guards against a kft.lbf label)
    assert!(after(lo, "torque ").0 > 1000.0);
    let (ls, lo) = (line(&si, "contacts:"), line(&oil, "contacts:"));
    agree(
        after(ls, "between "),
        after(lo, "between "),
        ("m", "ft"),
        FT,
        (0.1, 0.1),
    );

    // the stiff-BHA + soft-string level prints through its own path
    let (si, oil) = both(&["solve", &case, "--fidelity", "hybrid"]);
    let (ls, lo) = (line(&si, "stiff model cut"), line(&oil, "stiff model cut"));
    agree(after(ls, "cut "), after(lo, "cut "), ("m", "ft"), FT, (0.1, 0.1));
    let (ls, lo) = (line(&si, "surface:"), line(&oil, "surface:"));
    agree(
        after(ls, "hook load "),
        after(lo, "hook load "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.1, 0.1),
    );
    agree(
        after(ls, "torque "),
        after(lo, "torque "),
        ("kN.m", "ft.lbf"),
        FTLBF_KNM,
        (0.01, 1.0),
    );
    let (ls, lo) = (line(&si, "buckling:"), line(&oil, "buckling:"));
    agree(
        after(ls, "max compression "),
        after(lo, "max compression "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.1, 0.1),
    );
}

#[test]
fn predict_backanalyze_and_loads_print_in_the_chosen_units() {
    let seed = well("seed-daqing");
    let (si, oil) = both(&["predict", &seed, "--from", "292", "--to", "413", "--step", "5m"]);
    let (ls, lo) = (line(&si, "from "), line(&oil, "from "));
    agree(after(ls, "from "), after(lo, "from "), ("m", "ft"), FT, (0.01, 0.01));
    agree(after(ls, "TVD "), after(lo, "TVD "), ("m", "ft"), FT, (0.01, 0.01));
    let (ls, lo) = (line(&si, "build rate"), line(&oil, "build rate"));
    // as rates per length: 1 deg/100 ft = 30/30.48 deg/30 m
    agree(
        after(ls, "build rate "),
        after(lo, "build rate "),
        ("deg/30", "deg/100"),
        30.0 / 30.48,
        (0.001, 0.001),
    );
    agree(
        after(ls, "build force "),
        after(lo, "build force "),
        ("kN", "klbf"),
        KLBF_KN,
        (0.001, 0.001),
    );

    let (si, oil) = both(&["backanalyze", &seed, "--step", "5m", "--to", "600"]);
    let (ls, lo) = (line(&si, " intervals from "), line(&oil, " intervals from "));
    agree(after(ls, "from "), after(lo, "from "), ("m", "ft"), FT, (0.1, 0.1));
    // error per 100 m against per 100 ft: 1 deg/100 ft = 100/30.48 deg/100 m
    agree(
        after(ls, "inclination "),
        after(lo, "inclination "),
        ("deg/100", "deg/100"),
        100.0 / 30.48,
        (0.001, 0.001),
    );

    let (si, oil) = both(&["loads", &well("j-shape"), "--every", "500m"]);
    assert!(line(&si, "bit MD m |").contains("hook load kN") && line(&oil, "bit MD ft |").contains("torque ft.lbf"));
    let row = |t: &str| -> Vec<f64> {
        let l = t
            .lines()
            .rfind(|l| l.contains('|') && l.trim_start().starts_with(|c: char| c.is_ascii_digit()))
            .expect("a table row")
            .to_string();
        l.split(['|', ' '])
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect()
    };
    let (rs, ro) = (row(&si), row(&oil));
    assert_eq!(rs.len(), 9);
    assert!(
        (ro[0] * FT - rs[0]).abs() <= 0.05 + 0.05 * FT,
        "bit MD {} m vs {} ft",
        rs[0],
        ro[0]
    );
    for k in 1..6 {
        assert!(
            (ro[k] * KLBF_KN - rs[k]).abs() <= 0.05 * (1.0 + KLBF_KN),
            "hook load column {k}"
        );
    }
    for k in 6..8 {
        assert!(
            (ro[k] * FTLBF_KNM - rs[k]).abs() <= 0.005 + 0.5 * FTLBF_KNM,
            "torque column {k}"
        );
    }
}

/// `drillpath solve ... | head -1`: the reader is gone before the first line is written; the
/// command ends cleanly (exit 0, nothing on stderr) instead of panicking in println!.
#[test]
fn a_closed_stdout_pipe_is_a_clean_exit() {
    let case = well("j-shape");
    for args in [
        vec!["solve", &case, "--bit-md", "800 m"],
        vec!["solve", &case, "--bit-md", "800 m", "--json"],
    ] {
        let mut child = drillpath()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take()); // closes the read end: every write gets EPIPE
        let mut err = String::new();
        child.stderr.take().unwrap().read_to_string(&mut err).unwrap();
        let status = child.wait().unwrap();
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(status.code(), Some(0), "{args:?}: {err}");
        assert!(err.is_empty(), "{args:?}: {err}");
    }
}

/// The progress bar is drawn on a terminal (a pty from util-linux `script`) and not with -q;
/// into a pipe stderr stays empty (checked in every `both` run above and here).
#[test]
fn progress_bar_only_on_a_terminal_and_not_with_quiet() {
    let seed = well("seed-daqing");
    let args = ["predict", seed.as_str(), "--from", "292", "--to", "330", "--step", "5m"];
    let piped = run(&args);
    assert!(piped.stderr.is_empty());
    let have_script = Command::new("script")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !have_script {
        eprintln!("note: `script` (util-linux) not found; terminal progress not checked");
        return;
    }
    let exe = env!("CARGO_BIN_EXE_drillpath");
    let on_tty = |quiet: bool| -> String {
        let cmd = format!("'{exe}' {} {}", if quiet { "-q" } else { "" }, args.join(" "));
        let out = Command::new("script")
            .args(["-q", "-e", "-c", &cmd, "/dev/null"])
            .stdin(Stdio::null())
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let shown = on_tty(false);
    assert!(shown.contains("] ") && shown.contains("m of 330.0 m"), "{shown}");
    assert!(shown.contains("predict: "), "the summary is printed too");
    let quiet = on_tty(true);
    assert!(!quiet.contains("m of 330.0 m"), "{quiet}");
    assert!(quiet.contains("predict: "));
}

/// Log lines (`-vv`) on a terminal do not tear the progress bar: each is written on a cleared
/// line (after indicatif's `\r` + erase-line, or at the start of a line), never appended to the
/// bar's text. Reference: the escape sequences indicatif writes to clear its line.
#[test]
fn log_lines_do_not_tear_the_progress_bar() {
    let have_script = Command::new("script")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !have_script {
        eprintln!("note: `script` (util-linux) not found; terminal progress not checked");
        return;
    }
    let exe = env!("CARGO_BIN_EXE_drillpath");
    let seed = well("seed-daqing");
    let cmd = format!("'{exe}' -vv loads '{seed}' --from 700 --every 27 --fidelity whole");
    let out = Command::new("script")
        .args(["-q", "-e", "-c", &cmd, "/dev/null"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let raw = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{raw}");
    assert!(raw.contains("] 0/2"), "a bar is drawn: {raw}");
    let pieces: Vec<&str> = raw.split("DEBUG").collect();
    assert!(pieces.len() > 2, "debug lines are written: {raw}");
    // what stands on the terminal line before "DEBUG": the text after the last carriage return
    // or newline, without escape sequences (colour, erase line, cursor moves), must be empty
    let visible = |tail: &str| -> String {
        let mut text = String::new();
        let mut chars = tail.chars();
        while let Some(c) = chars.next() {
            if c == '\x1b' {
                for e in chars.by_ref() {
                    if e.is_ascii_alphabetic() {
                        break;
                    }
                }
            } else {
                text.push(c);
            }
        }
        text
    };
    for before in &pieces[..pieces.len() - 1] {
        let line = before.rsplit(['\r', '\n']).next().unwrap_or("");
        assert!(
            visible(line).is_empty(),
            "log line appended to other output: ...{:?}",
            &before[before.len().saturating_sub(120)..]
        );
    }
}

/// `solve --report` at the cut levels: the report shows the stiff part (bit to coupling
/// point) with a note naming the level; `hybrid` shows the soft string's hook load, `bha` says
/// it is not computed; `soft` (nothing stiff to draw) is refused before anything runs, with one
/// error naming `--report`, and no file.
#[test]
fn report_at_the_cut_levels() {
    let tmp = tempfile::tempdir().unwrap();
    for level in ["hybrid", "bha"] {
        let file = tmp.path().join(format!("{level}.html"));
        let out = run_in(
            root(),
            &[
                "solve",
                &well("j-shape"),
                "--fidelity",
                level,
                "--report",
                file.to_str().unwrap(),
            ],
        );
        assert!(out.success(), "{}", out.stderr);
        let html = std::fs::read_to_string(&file).unwrap();
        assert!(
            html.contains(&format!("Fidelity {level}: stiff model of the bottom")),
            "{level}"
        );
        assert_eq!(html.contains("not computed (bha)"), level == "bha", "{level}");
        assert!(!html.contains("NaN"));
    }
    let file = tmp.path().join("soft.html");
    let out = run_in(
        root(),
        &[
            "solve",
            &well("j-shape"),
            "--fidelity",
            "soft",
            "--report",
            file.to_str().unwrap(),
        ],
    );
    assert_eq!(out.code(), Some(2));
    let err = &out.stderr;
    assert!(err.contains("--report") && err.contains("soft"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!file.exists());
}
