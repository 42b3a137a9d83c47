//! Fuzz test of the input readers (issue 18): the survey reader
//! (`drillpath::io::survey::parse_survey`, CSV, text reports and WITSML trajectories) and the case reader
//! (`drillpath::io::case_toml::parse_case`) fed 26,000 generated inputs per run: random bytes
//! and text, valid survey CSVs, text reports and case files mutated byte by byte, word by word
//! and line by line, and the j-shape case with values replaced, removed and added.
//!
//! Reference (the issue's rule for bad input): no panic; every call returns, within
//! [`PER_INPUT`] each and [`PER_STRATEGY`] per strategy (a watchdog thread, so a hang fails
//! the test instead of stalling it); an error names its place: the file and a line
//! (1-based, inside the file) or a dotted key; only an empty file, or one of only comments, is
//! named as a whole file. What is read has no NaN or infinity, and a survey is valid (MD
//! strictly increasing, inclination in [0, 180] deg, azimuth in [0, 360) deg).
//!
//! Each input is a few kilobytes at most; the whole run takes about a second. Run with
//! `cargo test --release --test verification fuzz_input:: -- --nocapture` to see the counts
//! of inputs read and refused (by the kind of place named) and the times; set
//! `FUZZ_INPUT_SCALE=N` to run N times as many inputs. Failing inputs (shrunk) are kept in
//! `tests/verification/fuzz_input.proptest-regressions` and tried first on later runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::{Arc, LazyLock, Mutex};
use std::time::{Duration, Instant};

use drillpath::error::{InputError, Location};
use drillpath::io::case_toml::{parse_case, CaseOverrides};
use drillpath::io::survey::{parse_survey, SurveyUnits};
use drillpath::units::lookup;
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestRunner};

use crate::common::{example_case, example_dir};

/// Longest time one input may take (the inputs are small: a valid one reads in well under a
/// millisecond; the bound is generous for a shared machine).
const PER_INPUT: Duration = Duration::from_secs(2);

/// Longest time one strategy's run may take before the test is failed as a hang.
const PER_STRATEGY: Duration = Duration::from_secs(180);

/// Messages of the only errors allowed to name the whole file rather than a line or a key.
const WHOLE_FILE: &[&str] = &[
    "the survey file is empty",
    "the survey file contains only comments and blank lines",
    "the case file is empty",
];

// ----------------------------------------------------------------------------------------------
// Seeds: valid inputs the mutations start from
// ----------------------------------------------------------------------------------------------

/// The first `n` lines of `path` (with their line ends).
fn head(path: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    text.split_inclusive('\n').take(n).collect()
}

/// Valid survey CSVs: the readers' variants (units in brackets, suffixes, a units line,
/// `;` with decimal commas, tabs, quotes, qualified azimuths) and the heads of real files.
static CSV_SEEDS: LazyLock<Vec<String>> = LazyLock::new(|| {
    vec![
        "# test survey\nmd [m],inc [deg],azi [deg]\n0,0,0\n300,0,0\n600,10,45\n1000,20,45\n".into(),
        "Measured Depth ( ft ),Incl. ( deg ),Azimuth Grid ( deg ),TVD ( ft ),DLS (deg/100ft)\r\n0,0,0,0,0\r\n100,2,45,99.98,2\r\n200,4.5,47,199.8,2.5\r\n".into(),
        "MD,Inc,Azimuth True,TVD\n(ft),(deg),(deg),(ft)\n0,0,0,0\n100,1,2,100\n".into(),
        "md_ft;inc_deg;azi_rad\n0;0;0\n100,5;2,5;0,5\n".into(),
        "md\tinc\tazi\n0\t0\t0\n50\t1\t2\n".into(),
        "\u{feff}\"MD [ft]\",\"Inc\",\"Azi\",\"Note\"\n0,0,0,\"tie, in\"\n100,1,2,\"x\"\n".into(),
        head(&example_dir("forge-16b").join("16B78-32_survey.csv"), 12),
        head(&example_dir("j-shape").join("survey.csv"), 10),
        head(&example_dir("forge-16a").join("Directional_Survey16A-32.csv"), 8),
        head(&example_dir("volve-f10").join("15_9-F-10_actual_trajectory.csv"), 6),
    ]
});

/// Valid WITSML 1.4.1.1 trajectories: pretty-printed and on one line, m / ft, dega / rad, a
/// tie-in position, toolfaces, a projected station, two trajectories.
static XML_SEEDS: LazyLock<Vec<String>> = LazyLock::new(|| {
    let st = |uid: &str, kind: &str, md: &str, incl: &str, azi: &str| {
        format!("<trajectoryStation uid=\"{uid}\">\n<typeTrajStation>{kind}</typeTrajStation>\n<md uom=\"m\">{md}</md>\n<tvd uom=\"m\">{md}</tvd>\n<incl uom=\"dega\">{incl}</incl>\n<azi uom=\"dega\">{azi}</azi>\n<gtf uom=\"dega\">-20</gtf>\n<dispNs uom=\"m\">1.5</dispNs>\n<dispEw uom=\"m\">-2</dispEw>\n</trajectoryStation>\n")
    };
    let traj = |name: &str, body: &str| {
        format!("<trajectory uid=\"{name}\">\n<name>{name}</name>\n<magDeclUsed uom=\"dega\">-2.2</magDeclUsed>\n<gridCorUsed uom=\"rad\">-0.0166</gridCorUsed>\n<aziRef>grid north</aziRef>\n{body}</trajectory>\n")
    };
    let doc = |body: &str| {
        format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<trajectorys xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n{body}</trajectorys>\n")
    };
    let three = [
        st("a", "tie in point", "0", "0", "0"),
        st("b", "magnetic MWD", "150.5", "1.5", "182"),
        st("c", "gyro MWD", "300", "10", "190"),
    ]
    .concat();
    let pretty = doc(&traj(
        "T1",
        &format!("{three}{}", st("p", "hold to MD", "400", "10", "190")),
    ));
    vec![
        pretty.clone(),
        pretty.replace('\n', ""),
        pretty.replace("uom=\"m\"", "uom=\"ft\""),
        doc(&traj("T1", &three)).replace("uom=\"dega\">1", "uom=\"rad\">0.1"),
    ]
});

/// Valid text reports: the head of the FORGE 16B report and a made-up one.
static REPORT_SEEDS: LazyLock<Vec<String>> = LazyLock::new(|| {
    vec![
        head(&example_dir("forge-16b").join("16B78-32_Final_Survey_Report.txt"), 32),
        "COMPANY : Example\nNORTH REFERENCE : True North\n\nSurvey\nMD  Incl.  Azim  TVD\n(m) (deg) (deg) (m)\n0.0 0.00 0.00 0.0\n150.0 1,50 45.0 149.98\n300.0 3.00 50.0 299.9\n".into(),
        "MD (ft)  INC [deg]  AZI_GRID( deg )\n0 0 0\n100 1 2\n".into(),
    ]
});

/// The valid case of the j-shape example (read where it is, so that its survey is found).
static CASE_SEED: LazyLock<String> =
    LazyLock::new(|| std::fs::read_to_string(example_case("j-shape")).expect("read wells/j-shape/case.toml"));

/// Words the mutations put in place of a word of the input.
const WORDS: &[&str] = &[
    "",
    "NaN",
    "inf",
    "-inf",
    "1e309",
    "-1e309",
    "-0",
    "-1",
    "0",
    "1e-300",
    "180.0000001",
    "360",
    "0x10",
    "1,5",
    ",",
    ";",
    "\t",
    "\"",
    "\"\"",
    ":",
    " : ",
    "=",
    "#",
    "\r",
    "\n",
    "\r\n",
    "\u{feff}",
    "°",
    "\u{1F600}",
    "İ",
    "(ft)",
    "[deg]",
    "( ft )",
    "(furlong)",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    "[[string]]",
    "[well]",
    "Azimuth Grid",
    "Azimuth True",
    "AZI_TRUE",
    "Incl.",
    "MD",
    "INC",
    "AZI",
    "NORTH REF : Grid",
    "NORTH REF : True",
    "m",
    "ft",
    "deg",
    "rad",
    "km",
    "in",
    "\"1e400 m\"",
    "\"-5 m\"",
    "\"0 m\"",
    "\"1e-9 m\"",
    "\"1e9 m\"",
    "\"3 in\"",
    "\"30 in\"",
    "true",
    "[]",
    "{}",
    "survey",
    "hole",
    "to_md",
    "diameter",
    "bit_md",
    "wob",
    "length",
    "joint_length",
    "od",
    "id",
    "type",
    "pipe",
    "collar",
    "stabilizer",
    "bit",
    "\"survey.csv\"",
    "\"case.toml\"",
    "\"..\"",
    "\"\"",
    "1e308",
    "9007199254740993",
];

// ----------------------------------------------------------------------------------------------
// Mutations
// ----------------------------------------------------------------------------------------------

/// One change to an input; positions are taken modulo the input's length (or word or line
/// count) when applied.
#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, Vec<u8>),
    Delete(usize, usize),
    Byte(usize, u8),
    Word(usize, &'static str),
    Number(usize, f64),
    DuplicateLine(usize),
    DropLine(usize),
    SwapLines(usize, usize),
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let number = prop_oneof![
        any::<f64>(),
        -1e4..1e4f64,
        (-400i32..400).prop_map(f64::from),
        Just(f64::NAN),
        Just(f64::INFINITY),
    ];
    prop_oneof![
        (any::<usize>(), prop::collection::vec(any::<u8>(), 1..8)).prop_map(|(p, b)| Edit::Insert(p, b)),
        (any::<usize>(), 1..24usize).prop_map(|(p, n)| Edit::Delete(p, n)),
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Edit::Byte(p, b)),
        (any::<usize>(), prop::sample::select(WORDS)).prop_map(|(k, w)| Edit::Word(k, w)),
        (any::<usize>(), number).prop_map(|(k, v)| Edit::Number(k, v)),
        any::<usize>().prop_map(Edit::DuplicateLine),
        any::<usize>().prop_map(Edit::DropLine),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::SwapLines(a, b)),
        any::<usize>().prop_map(Edit::Truncate),
    ]
}

/// Byte ranges of the words of `b`: runs of bytes that are not white space or punctuation
/// (`,;:="'[](){}`).
fn words(b: &[u8]) -> Vec<(usize, usize)> {
    let sep = |c: u8| c.is_ascii_whitespace() || b",;:=\"'[](){}".contains(&c);
    let mut out = Vec::new();
    let mut start = None;
    for (i, &c) in b.iter().enumerate() {
        match (start, sep(c)) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, b.len()));
    }
    out
}

/// Byte ranges of the lines of `b`, line ends included.
fn lines(b: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &c) in b.iter().enumerate() {
        if c == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < b.len() {
        out.push((start, b.len()));
    }
    out
}

fn apply(b: &mut Vec<u8>, e: &Edit) {
    let n = b.len();
    match e {
        Edit::Insert(p, bytes) => {
            let p = p % (n + 1);
            b.splice(p..p, bytes.iter().copied());
        }
        Edit::Delete(p, len) if n > 0 => {
            let p = p % n;
            b.drain(p..(p + len).min(n));
        }
        Edit::Byte(p, v) if n > 0 => b[p % n] = *v,
        Edit::Word(k, w) => {
            let ws = words(b);
            if !ws.is_empty() {
                let (s, t) = ws[k % ws.len()];
                b.splice(s..t, w.bytes());
            }
        }
        Edit::Number(k, v) => {
            let ws: Vec<_> = words(b)
                .into_iter()
                .filter(|&(s, t)| std::str::from_utf8(&b[s..t]).is_ok_and(|w| w.parse::<f64>().is_ok()))
                .collect();
            if !ws.is_empty() {
                let (s, t) = ws[k % ws.len()];
                let text = if k % 2 == 0 { format!("{v}") } else { format!("{v:e}") };
                b.splice(s..t, text.bytes());
            }
        }
        Edit::DuplicateLine(k) | Edit::DropLine(k) => {
            let ls = lines(b);
            if !ls.is_empty() {
                let (s, t) = ls[k % ls.len()];
                if matches!(e, Edit::DropLine(_)) {
                    b.drain(s..t);
                } else {
                    let line = b[s..t].to_vec();
                    b.splice(t..t, line);
                }
            }
        }
        Edit::SwapLines(i, j) => {
            let ls = lines(b);
            if ls.len() > 1 {
                let (a, c) = (ls[i % ls.len()], ls[j % ls.len()]);
                let (first, second) = if a.0 <= c.0 { (a, c) } else { (c, a) };
                if first != second {
                    let mut out = b[..first.0].to_vec();
                    out.extend_from_slice(&b[second.0..second.1]);
                    out.extend_from_slice(&b[first.1..second.0]);
                    out.extend_from_slice(&b[first.0..first.1]);
                    out.extend_from_slice(&b[second.1..]);
                    *b = out;
                }
            }
        }
        Edit::Truncate(p) => b.truncate(p % (n + 1)),
        Edit::Delete(..) | Edit::Byte(..) => {}
    }
}

/// One of `seeds` changed by 1 to 6 edits.
fn mutated(seeds: &'static LazyLock<Vec<String>>) -> impl Strategy<Value = Vec<u8>> {
    (0..seeds.len(), prop::collection::vec(edit(), 1..7)).prop_map(move |(i, edits)| {
        let mut b = seeds[i].as_bytes().to_vec();
        for e in &edits {
            apply(&mut b, e);
        }
        b
    })
}

// ----------------------------------------------------------------------------------------------
// Checks
// ----------------------------------------------------------------------------------------------

/// Number of lines of `bytes` (a last line without its end counted; at least 1).
fn line_count(bytes: &[u8]) -> usize {
    lines(bytes).len().max(1)
}

/// `e` names its place: its file is one of `files` (path, line count) or an existing file,
/// and a line inside it or a key; or it is one of the [`WHOLE_FILE`] errors. Returns what kind
/// of place it names (for the counts).
fn check_placed(e: &InputError, files: &[(&Path, usize)]) -> Result<&'static str, TestCaseError> {
    let text = e.to_string();
    prop_assert!(!e.message.trim().is_empty(), "empty message: {text}");
    let (file, kind) = match &e.location {
        Location::File(f) => {
            prop_assert!(
                WHOLE_FILE.iter().any(|m| e.message.starts_with(m)),
                "error naming neither a line nor a key: {text}"
            );
            (f, "error: whole file")
        }
        Location::Line { file, line, column } => {
            let n = match files.iter().find(|(p, _)| p == file) {
                Some((_, n)) => *n,
                None => line_count(&std::fs::read(file).unwrap_or_default()),
            };
            prop_assert!(
                *line >= 1 && *line <= n,
                "line {line} is not a line of the file ({n} lines): {text}"
            );
            if let Some(c) = column {
                prop_assert!(text.contains(&format!("column `{c}`")), "{text}");
            }
            (file, "error: line")
        }
        Location::Key { file, key } => {
            prop_assert!(!key.is_empty(), "empty key: {text}");
            prop_assert!(text.contains(&format!("key `{key}`")), "{text}");
            (file, "error: key")
        }
        Location::Element { file, line, element } => {
            let n = match files.iter().find(|(p, _)| p == file) {
                Some((_, n)) => *n,
                None => line_count(&std::fs::read(file).unwrap_or_default()),
            };
            prop_assert!(
                *line >= 1 && *line <= n && !element.is_empty(),
                "line {line} is not a line of the file ({n} lines): {text}"
            );
            (file, "error: element")
        }
        Location::Option(o) => {
            return Err(TestCaseError::fail(format!("a file error named as option {o}: {text}")));
        }
    };
    prop_assert!(
        text.starts_with(&file.display().to_string()),
        "the error does not start with its file: {text}"
    );
    Ok(kind)
}

/// Run `f` and fail if it takes longer than [`PER_INPUT`].
fn timed<T>(f: impl FnOnce() -> T) -> Result<T, TestCaseError> {
    let t0 = Instant::now();
    let out = f();
    let dt = t0.elapsed();
    prop_assert!(dt <= PER_INPUT, "one input took {:.2} s", dt.as_secs_f64());
    Ok(out)
}

/// The unit settings a survey is read with: none, the case's `survey_md_unit = "ft"`, angles
/// in rad.
fn survey_units(k: usize) -> SurveyUnits {
    match k % 3 {
        0 => SurveyUnits::default(),
        1 => SurveyUnits {
            md: lookup("ft"),
            ..Default::default()
        },
        _ => SurveyUnits {
            md: None,
            angle: lookup("rad"),
            ..Default::default()
        },
    }
}

/// Read `bytes` as the survey file `name`: a valid survey or an error naming its place.
fn check_survey(bytes: &[u8], name: &str, units: &SurveyUnits) -> Result<&'static str, TestCaseError> {
    let path = Path::new(name);
    match timed(|| parse_survey(bytes, path, units))? {
        Ok(f) => {
            let st = f.survey.stations();
            prop_assert!(!st.is_empty());
            for (i, s) in st.iter().enumerate() {
                prop_assert!(
                    s.md_m.is_finite() && s.inc_rad.is_finite() && s.azi_rad.is_finite(),
                    "{s:?}"
                );
                prop_assert!((0.0..=std::f64::consts::PI).contains(&s.inc_rad), "{s:?}");
                prop_assert!((0.0..std::f64::consts::TAU).contains(&s.azi_rad), "{s:?}");
                prop_assert!(i == 0 || s.md_m > st[i - 1].md_m, "MD not increasing at {i}");
            }
            let n = line_count(bytes);
            prop_assert_eq!(f.station_lines.len(), st.len());
            // a WITSML file may hold several stations on one line
            prop_assert!(f
                .station_lines
                .windows(2)
                .all(|w| w[0] < w[1] || (name.ends_with(".xml") && w[0] <= w[1])));
            prop_assert!(f.station_lines.iter().all(|&l| l >= 1 && l <= n));
            Ok("read")
        }
        Err(e) => check_placed(&e, &[(path, line_count(bytes))]),
    }
}

/// The text of `debug` without its quoted strings (user text may hold `NaN`).
fn unquoted(debug: &str) -> String {
    let mut out = String::with_capacity(debug.len());
    let mut in_string = false;
    let mut escaped = false;
    for c in debug.chars() {
        if in_string {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                in_string = false;
            }
        } else if c == '"' {
            in_string = true;
        } else {
            out.push(c);
        }
    }
    out
}

/// Read `bytes` as the j-shape example's case file: a case without NaN or infinity, or an
/// error naming its place.
fn check_case(bytes: &[u8]) -> Result<&'static str, TestCaseError> {
    let path: PathBuf = example_case("j-shape");
    match timed(|| parse_case(bytes, &path, &CaseOverrides::default()))? {
        Ok(case) => {
            let debug = unquoted(&format!("{case:?}"));
            let bad = debug
                .split(|c: char| !c.is_ascii_alphanumeric())
                .find(|w| matches!(*w, "NaN" | "inf"));
            prop_assert!(bad.is_none(), "the case read holds a non-finite number: {bad:?}");
            Ok("read")
        }
        Err(e) => check_placed(&e, &[(&path, line_count(bytes))]),
    }
}

// ----------------------------------------------------------------------------------------------
// The runs
// ----------------------------------------------------------------------------------------------

/// What a check returns: how the input was taken (`read`, or the kind of place its error
/// names).
type Check<V> = fn(&V) -> Result<&'static str, TestCaseError>;

/// Run `check` on `cases` values of `strategy` in a worker thread; fail on the first failing
/// input (shrunk) or if the run takes longer than [`PER_STRATEGY`]; print the outcomes' counts.
fn fuzz<S>(name: &'static str, cases: u32, strategy: S, check: Check<S::Value>)
where
    S: Strategy + Send + 'static,
{
    let scale = std::env::var("FUZZ_INPUT_SCALE")
        .ok()
        .and_then(|v| v.parse::<u32>().ok())
        .unwrap_or(1)
        .max(1);
    let cases = cases.saturating_mul(scale);
    let (tx, rx) = channel();
    let t0 = Instant::now();
    let counts = Arc::new(Mutex::new(BTreeMap::<&'static str, usize>::new()));
    let tally = Arc::clone(&counts);
    std::thread::spawn(move || {
        let mut runner = TestRunner::new(Config {
            cases,
            failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
            source_file: Some(file!()),
            ..Config::default()
        });
        let result = runner.run(&strategy, |v| {
            let outcome = check(&v)?;
            if let Ok(mut c) = tally.lock() {
                *c.entry(outcome).or_default() += 1;
            }
            Ok(())
        });
        let _ = tx.send(result.map_err(|e| e.to_string()));
    });
    match rx.recv_timeout(PER_STRATEGY) {
        Ok(Ok(())) => println!(
            "{name}: {cases} inputs in {:.2} s: {:?}",
            t0.elapsed().as_secs_f64(),
            counts.lock().map(|c| c.clone()).unwrap_or_default()
        ),
        Ok(Err(e)) => panic!("{name}: {e}"),
        Err(RecvTimeoutError::Timeout) => panic!(
            "{name}: no result after {} s: a reader hangs (or FUZZ_INPUT_SCALE is too large)",
            PER_STRATEGY.as_secs()
        ),
        Err(RecvTimeoutError::Disconnected) => panic!("{name}: the fuzzing thread died"),
    }
}

#[test]
fn fuzz_survey_reader_with_random_bytes() {
    let strategy = (prop::collection::vec(any::<u8>(), 0..600), 0..3usize);
    fuzz("survey, random bytes", 4000, strategy, |(b, k)| {
        check_survey(b, "random.csv", &survey_units(*k))
    });
}

#[test]
fn fuzz_survey_reader_with_mutated_csvs() {
    fuzz(
        "survey, mutated CSVs",
        6000,
        (mutated(&CSV_SEEDS), 0..3usize),
        |(b, k)| check_survey(b, "mutated.csv", &survey_units(*k)),
    );
}

#[test]
fn fuzz_survey_reader_with_mutated_witsml() {
    fuzz(
        "survey, mutated WITSML",
        4000,
        (mutated(&XML_SEEDS), 0..3usize),
        |(b, k)| check_survey(b, "mutated.xml", &survey_units(*k)),
    );
}

#[test]
fn fuzz_survey_reader_with_mutated_text_reports() {
    fuzz(
        "survey, mutated text reports",
        5000,
        (mutated(&REPORT_SEEDS), 0..3usize),
        |(b, k)| check_survey(b, "mutated-report.txt", &survey_units(*k)),
    );
}

static CASE_SEEDS: LazyLock<Vec<String>> = LazyLock::new(|| vec![CASE_SEED.clone()]);

#[test]
fn fuzz_case_reader_with_mutated_cases() {
    fuzz("case, mutated j-shape case.toml", 4000, mutated(&CASE_SEEDS), |b| {
        check_case(b)
    });
}

// ----------------------------------------------------------------------------------------------
// Case files changed value by value (still valid TOML, so the checks past the syntax are reached)
// ----------------------------------------------------------------------------------------------

/// Words the case file's string values take, beside its keys ([`case_words`]).
const VALUE_WORDS: &[&str] = &[
    "drilling",
    "sliding",
    "rotating",
    "trip_in",
    "trip_out",
    "bit",
    "pipe",
    "collar",
    "hwdp",
    "stabilizer",
    "motor",
    "auto",
    "soft",
    "bha",
    "hybrid",
    "whole",
    "newton",
    "paper",
    "ho",
    "S-135",
    "G-105",
    "steel",
    "aluminium",
    "titanium",
    "survey.csv",
    "case.toml",
    "../forge-16b/16B78-32_Final_Survey_Report.txt",
    "../forge-16b/16B78-32_survey.csv",
    "..",
    "",
];

/// Keys of the case file (every table's, from the reader) and words its string values take,
/// for values put in place of others.
fn case_words() -> Vec<&'static str> {
    let mut words = drillpath::io::case_toml::known_keys();
    words.extend_from_slice(VALUE_WORDS);
    words
}

/// Units of the quantities a case file holds (and a few it must refuse).
const CASE_UNITS: &[&str] = &[
    "", "m", "ft", "in", "mm", "km", "kN", "klbf", "N", "sg", "ppg", "kg/m3", "lb/ft", "kg/m", "m/h", "ft/h", "m/s",
    "rpm", "deg", "rad", "deg/30m", "cP", "Pa.s", "GPa", "psi", "kN.m", "ft.lbf", "-", "furlong",
];

/// A TOML value of any kind, numbers in every range (NaN and infinities included, which TOML
/// writes `nan` and `inf`).
fn toml_value() -> impl Strategy<Value = toml::Value> {
    use toml::Value as V;
    let number = prop_oneof![
        any::<f64>(),
        -1e4..1e4f64,
        (-400i32..4000).prop_map(f64::from),
        prop::sample::select(vec![
            0.0,
            -0.0,
            1e-300,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY
        ]),
    ];
    prop_oneof![
        3 => (number.clone(), prop::sample::select(CASE_UNITS)).prop_map(|(v, u)| V::String(format!("{v} {u}"))),
        2 => number.prop_map(V::Float),
        1 => any::<i64>().prop_map(V::Integer),
        2 => (-5i64..5000).prop_map(V::Integer),
        1 => any::<bool>().prop_map(V::Boolean),
        2 => prop::sample::select(case_words()).prop_map(|w| V::String(w.to_string())),
        1 => prop::sample::select(WORDS).prop_map(|w| V::String(w.to_string())),
        1 => Just(V::Array(vec![])),
        1 => Just(V::Table(toml::Table::new())),
        1 => prop::collection::vec((-10.0..5000.0f64).prop_map(V::Float), 0..5).prop_map(V::Array),
    ]
}

/// One change to the case's TOML document; the node is taken modulo the number of nodes (every
/// table, array and value, in document order).
#[derive(Debug, Clone)]
enum ValueEdit {
    Set(usize, toml::Value),
    /// Multiply the number of a value (`120 kN`, `0.25`) by a factor, keeping its unit.
    Scale(usize, f64),
    Remove(usize),
    Add(usize, &'static str, toml::Value),
}

fn value_edit() -> impl Strategy<Value = ValueEdit> {
    let factor = prop_oneof![
        prop::sample::select(vec![0.0, -1.0, 1e-9, 1e-3, 0.1, 0.5, 0.9, 1.1, 2.0, 10.0, 1e3, 1e9]),
        0.0..3.0f64,
    ];
    prop_oneof![
        5 => (any::<usize>(), toml_value()).prop_map(|(k, v)| ValueEdit::Set(k, v)),
        5 => (any::<usize>(), factor).prop_map(|(k, f)| ValueEdit::Scale(k, f)),
        2 => any::<usize>().prop_map(ValueEdit::Remove),
        2 => (any::<usize>(), prop::sample::select(case_words()), toml_value()).prop_map(|(k, w, v)| ValueEdit::Add(k, w, v)),
    ]
}

/// Apply `f` to the `k`-th node of `v` (pre-order, `v` itself first); `k` counts down.
fn visit(v: &mut toml::Value, k: &mut usize, f: &mut dyn FnMut(&mut toml::Value) -> Remove) -> Remove {
    if *k == 0 {
        return f(v);
    }
    *k -= 1;
    match v {
        toml::Value::Table(t) => {
            let keys: Vec<String> = t.keys().cloned().collect();
            for key in keys {
                if let Some(child) = t.get_mut(&key) {
                    if visit(child, k, f) == Remove::Yes {
                        t.remove(&key);
                        return Remove::No;
                    }
                }
            }
        }
        toml::Value::Array(a) => {
            for i in 0..a.len() {
                if visit(&mut a[i], k, f) == Remove::Yes {
                    a.remove(i);
                    return Remove::No;
                }
            }
        }
        _ => {}
    }
    Remove::No
}

/// Whether [`visit`]'s caller should remove the node it visited.
#[derive(Debug, PartialEq)]
enum Remove {
    Yes,
    No,
}

/// Number of nodes of `v` (itself included).
fn nodes(v: &toml::Value) -> usize {
    1 + match v {
        toml::Value::Table(t) => t.values().map(nodes).sum(),
        toml::Value::Array(a) => a.iter().map(nodes).sum(),
        _ => 0,
    }
}

/// Multiply the number of `v` by `f`: a float, an integer (rounded) or the number before the
/// unit of a quantity string; other values are left.
fn scale(v: &mut toml::Value, f: f64) {
    match v {
        toml::Value::Float(x) => *x *= f,
        toml::Value::Integer(i) => *i = (*i as f64 * f).round() as i64,
        toml::Value::String(s) => {
            let (num, unit) = s.split_once(' ').unwrap_or((s.as_str(), ""));
            if let Ok(x) = num.parse::<f64>() {
                *s = format!("{} {unit}", x * f).trim_end().to_string();
            }
        }
        _ => {}
    }
}

/// The j-shape case changed by 1 or 2 value edits, written back as TOML (comments dropped).
fn value_mutated_case() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(value_edit(), 1..3).prop_map(|edits| {
        let table: toml::Table = CASE_SEED.parse().expect("the j-shape case is TOML");
        let mut doc = toml::Value::Table(table);
        for e in &edits {
            let n = nodes(&doc);
            let (mut k, remove) = match e {
                ValueEdit::Add(k, ..) => (k % n, false),
                // never the document itself
                ValueEdit::Set(k, _) | ValueEdit::Scale(k, _) => (1 + k % (n - 1).max(1), false),
                ValueEdit::Remove(k) => (1 + k % (n - 1).max(1), true),
            };
            visit(&mut doc, &mut k, &mut |node| match e {
                _ if remove => Remove::Yes,
                ValueEdit::Set(_, v) => {
                    *node = v.clone();
                    Remove::No
                }
                ValueEdit::Scale(_, f) => {
                    scale(node, *f);
                    Remove::No
                }
                ValueEdit::Add(_, key, v) => {
                    if let toml::Value::Table(t) = node {
                        t.insert(key.to_string(), v.clone());
                    }
                    Remove::No
                }
                ValueEdit::Remove(_) => Remove::Yes,
            });
        }
        toml::to_string(&doc).unwrap_or_default().into_bytes()
    })
}

#[test]
fn fuzz_case_reader_with_changed_values() {
    fuzz(
        "case, j-shape case.toml with changed values",
        6000,
        value_mutated_case(),
        |b| check_case(b),
    );
}

#[test]
fn fuzz_case_reader_with_random_text() {
    let strategy = prop_oneof![
        prop::collection::vec(any::<u8>(), 0..400),
        "\\PC{0,300}".prop_map(String::into_bytes),
        "(\\[[a-z_]{1,10}\\]\n|[a-z_]{1,10} = (\"[0-9a-z .]{0,10}\"|[0-9.e-]{1,8}|true|\\[\\])\n){0,12}"
            .prop_map(String::into_bytes),
    ];
    fuzz("case, random text", 1000, strategy, |b| check_case(b));
}
