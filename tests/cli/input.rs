//! Command-line input handling of `drillpath survey`: every malformed input exits non-zero with
//! exactly one `error: ...` line on stderr that names the place (file and line / column, or the
//! dotted case-file key), never panics, and never leaves an output file behind. Plus the
//! positive paths on the example wells.
//!
//! Each test runs the built binary in a fresh temporary directory holding a small valid case
//! (`case.toml` + `survey.csv`), then breaks exactly one thing.

use std::path::Path;
use std::sync::LazyLock;
use tempfile::TempDir;

use crate::common::{
    assert_error_names, case_dir, collar, example_case, example_dir, run_in, stabilizer, Run, BIT, DRILL_PIPE,
    DRILL_PIPE_BODY,
};

/// The valid survey. Line 1 is a comment, so the header is line 2 and the stations are lines
/// 3 to 6 (errors must count lines of the original file).
const SURVEY: &str = "\
# test survey: vertical to 300 m, then building at azimuth 45 deg
md [m],inc [deg],azi [deg]
0,0,0
300,0,0
600,10,45
1000,20,45
";

/// The valid case. Components: string[0] bit, string[1] full-gauge stabilizer, string[2] 50 m
/// of 6.5 in collars, string[3] 5 in drill pipe (no length: fills to surface).
static CASE: LazyLock<String> = LazyLock::new(|| {
    format!(
        r#"name = "input test"

[well]
survey = "survey.csv"
hole = [
  {{ to_md = "500 m", diameter = "12.25 in", friction = 0.2 }},
  {{ to_md = "1000 m", diameter = "8.5 in" }},
]

[mud]
density = "1.2 sg"

[operation]
mode = "drilling"
bit_md = "1000 m"
wob = "100 kN"
rpm = 60

{BIT}
{}
{}
{DRILL_PIPE}
[solver]
element_length = "1 m"
"#,
        stabilizer("8.5 in"),
        collar("50 m")
    )
});

/// The exact header of `survey --out` (docs/guide.md).
const SURVEY_HEADER: &str = "md_m,inc_deg,azi_deg,tvd_m,north_m,east_m,dls_deg_per_30m";

/// A temporary directory with the valid case and survey.
struct Fixture {
    dir: TempDir,
}

impl Fixture {
    fn new() -> Self {
        Fixture {
            dir: case_dir(SURVEY, &CASE),
        }
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }

    fn write(&self, name: &str, text: &str) {
        std::fs::write(self.path().join(name), text).expect("cannot write a test file");
    }

    fn remove(&self, name: &str) {
        std::fs::remove_file(self.path().join(name)).expect("cannot remove a test file");
    }

    /// Replace the one occurrence of `old` in the valid `base` text and write it as `name`
    /// (the test fails if `old` is not there exactly once, so it cannot silently test nothing).
    fn edit(&self, name: &str, base: &str, old: &str, new: &str) {
        assert_eq!(
            base.matches(old).count(),
            1,
            "`{old}` must occur exactly once in the base {name}"
        );
        self.write(name, &base.replacen(old, new, 1));
    }

    fn edit_case(&self, old: &str, new: &str) {
        self.edit("case.toml", &CASE, old, new);
    }

    fn edit_survey(&self, old: &str, new: &str) {
        self.edit("survey.csv", SURVEY, old, new);
    }

    fn run(&self, args: &[&str]) -> Run {
        run_in(self.path(), args)
    }

    /// Run `args` plus `--out out.csv`, expect a clean failure whose message contains every
    /// string of `must_name` (the place and what is wrong); no output file may be left behind.
    fn expect_error(&self, args: &[&str], must_name: &[&str]) -> String {
        let mut all: Vec<&str> = args.to_vec();
        all.extend(["--out", "out.csv"]);
        let r = self.run(&all);
        check_error(&r, must_name);
        assert!(
            !self.path().join("out.csv").exists(),
            "an output file was written despite the error\n{}",
            r.describe()
        );
        let leftovers: Vec<String> = std::fs::read_dir(self.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("out.csv"))
            .collect();
        assert!(leftovers.is_empty(), "temporary output left behind: {leftovers:?}");
        r.stderr.trim_end().to_string()
    }
}

/// A user error: non-zero exit (not a signal), exactly one stderr line `error: ...` naming
/// every string of `must_name`, no panic or backtrace ([`assert_error_names`]), and nothing on
/// stdout.
fn check_error(r: &Run, must_name: &[&str]) {
    assert_error_names(r, must_name);
    assert!(
        r.stdout.trim().is_empty(),
        "nothing should be printed on stdout on error\n{}",
        r.describe()
    );
}

// ---------------------------------------------------------------------------------------------
// The fixture itself is valid (otherwise every error test below proves nothing).

#[test]
fn fixture_case_and_survey_are_valid() {
    let fx = Fixture::new();
    let r = fx.run(&["survey", "case.toml", "--out", "out.csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert!(r.stderr.trim().is_empty(), "{}", r.describe());
    assert!(r.stdout.contains("stations: 4"), "{}", r.describe());
    let csv = std::fs::read_to_string(fx.path().join("out.csv")).unwrap();
    assert_eq!(csv.lines().count(), 5, "{csv}");

    let r = fx.run(&["survey", "survey.csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert!(r.stdout.contains("stations: 4"), "{}", r.describe());
}

#[test]
fn string_above_the_first_survey_station_is_a_stated_assumption() {
    // A survey that starts at a tie-in (here 300 m) while the string reaches the surface: the
    // hole above is extrapolated straight along the first station (WellPath::point_at), which
    // changes the hook load. The solve still runs, but says so: one warning on stderr naming
    // the file and the MDs, and the same text under `notes` in the JSON summary. The complete
    // survey gives no note.
    let fx = Fixture::new();
    let full = fx.run(&["solve", "case.toml", "--json"]);
    assert_eq!(full.code(), Some(0), "{}", full.describe());
    assert!(full.stderr.trim().is_empty(), "{}", full.describe());
    let json: serde_json::Value = serde_json::from_str(&full.stdout).unwrap();
    assert_eq!(json["notes"], serde_json::json!([]), "{}", full.describe());

    fx.edit_survey("azi [deg]\n0,0,0\n", "azi [deg]\n");
    for fidelity in ["whole", "soft"] {
        let r = fx.run(&["solve", "case.toml", "--json", "--fidelity", fidelity]);
        assert_eq!(r.code(), Some(0), "{}", r.describe());
        let warning: Vec<&str> = r.stderr.lines().filter(|l| l.contains("WARN")).collect();
        assert_eq!(warning.len(), 1, "{}", r.describe());
        for must in [
            "case.toml",
            "survey starts at 300.0 m MD",
            "up to 0.0 m MD",
            "straight line",
        ] {
            assert!(warning[0].contains(must), "`{must}` missing\n{}", r.describe());
        }
        let json: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let notes = json["notes"].as_array().expect("a notes array");
        assert_eq!(notes.len(), 1, "{}", r.describe());
        assert!(notes[0].as_str().unwrap().contains("survey starts at 300.0 m MD"));
    }
}

// ---------------------------------------------------------------------------------------------
// Survey CSV errors: file, line of the original file (comments counted) and column.

#[test]
fn empty_survey_file() {
    let fx = Fixture::new();
    fx.write("survey.csv", "");
    fx.expect_error(&["survey", "case.toml"], &["survey.csv", "empty"]);
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "empty"]);
}

#[test]
fn survey_with_header_only() {
    let fx = Fixture::new();
    fx.write("survey.csv", "# nothing measured yet\nmd [m],inc [deg],azi [deg]\n");
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "line 2", "no data rows"]);
    fx.expect_error(&["survey", "case.toml"], &["survey.csv", "line 2"]);
}

#[test]
fn survey_missing_inc_column() {
    let fx = Fixture::new();
    fx.write(
        "survey.csv",
        "# no inclination\nmd [m],azi [deg]\n0,0\n300,0\n600,45\n1000,45\n",
    );
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "line 2", "inclination"]);
}

#[test]
fn survey_non_numeric_value() {
    let fx = Fixture::new();
    fx.edit_survey("600,10,45", "600,ten,45");
    fx.expect_error(
        &["survey", "case.toml"],
        &["survey.csv", "line 5", "column `inc [deg]`", "`ten`", "not a number"],
    );
}

#[test]
fn survey_nan_value() {
    let fx = Fixture::new();
    fx.edit_survey("300,0,0", "300,0,NaN");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 4", "column `azi [deg]`", "NaN"],
    );
}

#[test]
fn survey_infinite_md() {
    let fx = Fixture::new();
    fx.edit_survey("1000,20,45", "inf,20,45");
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "line 6", "column `md [m]`"]);
}

#[test]
fn survey_decreasing_md() {
    let fx = Fixture::new();
    fx.edit_survey("600,10,45", "200,10,45");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 5", "column `md [m]`", "line 4", "strictly increase"],
    );
}

#[test]
fn survey_repeated_md() {
    let fx = Fixture::new();
    fx.edit_survey("600,10,45", "300,10,45");
    fx.expect_error(&["survey", "case.toml"], &["survey.csv", "line 5", "column `md [m]`"]);
}

#[test]
fn survey_inclination_200() {
    let fx = Fixture::new();
    fx.edit_survey("1000,20,45", "1000,200,45");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 6", "column `inc [deg]`", "200", "[0, 180]"],
    );
}

#[test]
fn survey_negative_inclination() {
    let fx = Fixture::new();
    fx.edit_survey("600,10,45", "600,-10,45");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 5", "column `inc [deg]`"],
    );
}

#[test]
fn survey_unknown_unit_in_header() {
    let fx = Fixture::new();
    fx.edit_survey("md [m]", "md [furlong]");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 2", "column `md [furlong]`", "furlong"],
    );
}

#[test]
fn survey_row_with_too_few_fields() {
    let fx = Fixture::new();
    fx.edit_survey("600,10,45", "600,10");
    fx.expect_error(
        &["survey", "survey.csv"],
        &["survey.csv", "line 5", "column `azi [deg]`"],
    );
}

#[test]
fn survey_with_two_inclination_columns() {
    let fx = Fixture::new();
    fx.write("survey.csv", "md,inc,inclination,azi\n0,0,0,0\n10,1,1,0\n");
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "line 1", "inclination"]);
}

#[test]
fn survey_md_unit_in_case_contradicts_header() {
    let fx = Fixture::new();
    fx.edit_case(
        "survey = \"survey.csv\"",
        "survey = \"survey.csv\"\nsurvey_md_unit = \"ft\"",
    );
    fx.expect_error(
        &["survey", "case.toml"],
        &["survey.csv", "line 2", "column `md [m]`", "ft"],
    );
}

#[test]
fn missing_survey_file_named_by_the_case() {
    let fx = Fixture::new();
    fx.remove("survey.csv");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`well.survey`", "survey.csv"]);
}

#[test]
fn missing_survey_file_on_the_command_line() {
    let fx = Fixture::new();
    fx.expect_error(&["survey", "nowhere.csv"], &["nowhere.csv"]);
}

#[test]
fn missing_case_file() {
    let fx = Fixture::new();
    fx.expect_error(&["survey", "nowhere.toml"], &["nowhere.toml", "cannot read"]);
}

#[test]
fn md_unit_option_furlong() {
    let fx = Fixture::new();
    fx.expect_error(
        &["survey", "case.toml", "--md-unit", "furlong"],
        &["--md-unit", "furlong"],
    );
    fx.expect_error(
        &["survey", "survey.csv", "--md-unit", "furlong"],
        &["--md-unit", "furlong"],
    );
}

#[test]
fn md_unit_option_of_the_wrong_dimension() {
    let fx = Fixture::new();
    fx.expect_error(&["survey", "survey.csv", "--md-unit", "kN"], &["--md-unit", "kN"]);
}

// ---------------------------------------------------------------------------------------------
// Survey exports (issue 18 (9)): report-style headers, the azimuth reference, text reports.

/// The fixture's survey as a report exporter writes it: units in parentheses with spaces,
/// `Incl.`, a grid azimuth and a column not read.
const EXPORTED_SURVEY: &str = "\
Measured Depth ( m ),Incl. ( deg ),Azimuth Grid ( deg ),DLS (deg/30m)
0,0,0,0
300,0,0,0
600,10,45,1
1000,20,45,0.75
";

/// The fixture's survey as a whitespace-separated text report: metadata (grid north), a
/// title, the header, its units line and the stations, one more column than read.
const REPORT: &str = "\
COMPANY      : Example
NORTH REF    : Grid
DATE         : 1/2/2024

SURVEY
MD       INC      AZI      TVD
(m)      (deg)    (deg)    (m)

0.00     0.00     0.00     0.00
300.00   0.00     0.00     300.00
600.00   10.00    45.00    598.48
1000.00  20.00    45.00    984.32
";

#[test]
fn survey_with_exported_headers_names_the_grid_reference() {
    // Exported report headers: `Incl.` and `Azimuth Grid` are column names.
    let fx = Fixture::new();
    fx.write("survey.csv", EXPORTED_SURVEY);
    let plain = fx.run(&["survey", "case.toml", "--csv"]);
    for args in [["survey", "survey.csv"], ["survey", "case.toml"]] {
        let r = fx.run(&args);
        assert_eq!(r.code(), Some(0), "{}", r.describe());
        assert!(r.stdout.contains("stations: 4"), "{}", r.describe());
        assert!(
            r.stdout
                .contains("azimuth reference: grid north (from column `Azimuth Grid ( deg )`)"),
            "{}",
            r.describe()
        );
    }
    // the same positions as the fixture's plain survey
    fx.write("survey.csv", SURVEY);
    let r = fx.run(&["survey", "case.toml", "--csv"]);
    assert_eq!(r.stdout, plain.stdout);
    let r = fx.run(&["survey", "survey.csv"]);
    assert!(
        r.stdout
            .contains("azimuth reference: not stated in the survey file (azimuths used as written)"),
        "{}",
        r.describe()
    );
}

#[test]
fn survey_with_grid_and_true_azimuths_is_refused_naming_both() {
    let fx = Fixture::new();
    fx.write(
        "survey.csv",
        "MD (m),Inc (deg),Azimuth Grid (deg),Azimuth True (deg)\n0,0,0,0.5\n100,1,10,10.5\n",
    );
    fx.expect_error(
        &["survey", "survey.csv"],
        &[
            "survey.csv",
            "line 1",
            "`Azimuth Grid (deg)` (field 3, grid north)",
            "`Azimuth True (deg)` (field 4, true north)",
            "delete the column you do not want",
        ],
    );
}

#[test]
fn survey_text_report_reads_as_the_csv() {
    // A whitespace-separated report is read like a CSV.
    let fx = Fixture::new();
    fx.write("report.txt", REPORT);
    let r = fx.run(&["survey", "report.txt"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    for must in [
        "stations: 4",
        "note: read as a whitespace-separated survey report: header on line 6, units on line 7",
        "azimuth reference: grid north (from line 2 `NORTH REF : Grid`)",
    ] {
        assert!(r.stdout.contains(must), "`{must}` missing\n{}", r.describe());
    }
    let from_report = fx.run(&["survey", "report.txt", "--csv"]);
    let from_csv = fx.run(&["survey", "survey.csv", "--csv"]);
    assert_eq!(from_report.stdout, from_csv.stdout);
    // and named by a case
    fx.edit_case("survey = \"survey.csv\"", "survey = \"report.txt\"");
    let r = fx.run(&["survey", "case.toml", "--csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert_eq!(r.stdout, from_csv.stdout);
}

#[test]
fn survey_text_report_errors_name_the_line() {
    let fx = Fixture::new();
    fx.write(
        "report.txt",
        &REPORT.replace("600.00   10.00    45.00", "600.00   10.00"),
    );
    fx.expect_error(
        &["survey", "report.txt"],
        &["report.txt", "line 11", "3 fields", "header on line 6 names 4 columns"],
    );
    fx.write("report.txt", &REPORT.replace("1000.00  20.00", "1000.00  2O.00"));
    fx.expect_error(
        &["survey", "report.txt"],
        &["report.txt", "line 12", "column `INC`", "`2O.00` is not a number"],
    );
    fx.write("report.txt", &REPORT.replace("(m)      (deg)", "(furlong) (deg)"));
    fx.expect_error(
        &["survey", "report.txt"],
        &["report.txt", "line 7", "column `MD`", "furlong"],
    );
    fx.write("report.txt", &REPORT.replace("AZI ", "AZI_TRUE "));
    fx.expect_error(
        &["survey", "report.txt"],
        &[
            "report.txt",
            "line 2",
            "`Grid` (grid north) contradicts column `AZI_TRUE`",
        ],
    );
}

#[test]
fn forge_16b_report_reads_as_its_derived_csv() {
    // Reference: wells/forge-16b/16B78-32_survey.csv, derived value for value from the report
    // by wells/tools/forge16b_survey.py: the same positions, to the digit.
    let tmp = tempfile::tempdir().unwrap();
    let dir = example_dir("forge-16b");
    let report = dir.join("16B78-32_Final_Survey_Report.txt");
    let r = run_in(tmp.path(), &["survey", report.to_str().unwrap()]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    for must in [
        "stations: 428",
        "azimuth reference: grid north (from line 14 `NORTH REF : Grid`)",
        "header on line 21, units on line 22",
    ] {
        assert!(r.stdout.contains(must), "`{must}` missing\n{}", r.describe());
    }
    let from_report = run_in(tmp.path(), &["survey", report.to_str().unwrap(), "--csv"]);
    let csv = dir.join("16B78-32_survey.csv");
    let from_csv = run_in(tmp.path(), &["survey", csv.to_str().unwrap(), "--csv"]);
    assert_eq!(from_report.code(), Some(0), "{}", from_report.describe());
    assert_eq!(from_report.stdout.lines().count(), 429);
    assert_eq!(from_report.stdout, from_csv.stdout);
}

// ---------------------------------------------------------------------------------------------
// Case-file errors: the file and the dotted key.

#[test]
fn empty_case_file() {
    let fx = Fixture::new();
    fx.write("case.toml", "  \n");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "empty"]);
}

#[test]
fn unknown_key_typo_od_odd() {
    // The collar's `od` is misspelt: the key is then missing, and the message must point at
    // the collar (see also `typo_of_a_required_key_is_named` below).
    let fx = Fixture::new();
    fx.edit_case("type = \"collar\"\nod = ", "type = \"collar\"\nodd = ");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[2].od"]);
}

#[test]
fn unknown_key_typo_in_an_optional_key() {
    let fx = Fixture::new();
    fx.edit_case("weight = \"29 kg/m\"", "wieght = \"29 kg/m\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[3].wieght`", "unknown key", "`weight`"],
    );
}

#[test]
fn unknown_key_in_operation() {
    let fx = Fixture::new();
    fx.edit_case("wob = \"100 kN\"", "wob = \"100 kN\"\nweight_on_bit = \"100 kN\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`operation.weight_on_bit`", "unknown key"],
    );
}

#[test]
fn unknown_top_level_table() {
    let fx = Fixture::new();
    fx.edit_case("[solver]\n", "[solverr]\n");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`solverr`", "unknown key", "`solver`"],
    );
}

#[test]
fn negative_length() {
    let fx = Fixture::new();
    fx.edit_case("length = \"50 m\"", "length = \"-50 m\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[2].length`", "-50"]);
}

#[test]
fn id_not_smaller_than_od() {
    let fx = Fixture::new();
    fx.edit_case("od = \"5 in\"\nid = \"4.276 in\"", "od = \"5 in\"\nid = \"5 in\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[3].id`"]);
}

#[test]
fn component_wider_than_the_hole() {
    let fx = Fixture::new();
    fx.edit_case("type = \"collar\"\nod = \"6.5 in\"", "type = \"collar\"\nod = \"9 in\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[2].od`", "wider than the hole"],
    );
}

#[test]
fn bit_wider_than_the_hole() {
    let fx = Fixture::new();
    fx.edit_case("type = \"bit\"\nod = \"8.5 in\"", "type = \"bit\"\nod = \"8.75 in\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[0].od`", "wider than the hole"],
    );
}

#[test]
fn string_longer_than_the_hole() {
    // Every length given: 0.3 + 1.5 + 50 + 2000 m > 1000 m to the bit.
    let fx = Fixture::new();
    fx.edit_case("weight = \"29 kg/m\"", "weight = \"29 kg/m\"\nlength = \"2000 m\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string`", "longer than the hole"],
    );
}

#[test]
fn bha_longer_than_the_hole_with_fill_to_surface() {
    // The topmost component fills to surface but the components below already exceed the hole.
    let fx = Fixture::new();
    fx.edit_case("length = \"50 m\"", "length = \"1200 m\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[3].length`", "longer than the hole"],
    );
}

#[test]
fn toml_syntax_error_names_the_line() {
    let fx = Fixture::new();
    fx.edit_case("rpm = 60", "rpm = = 60");
    let line = CASE.lines().position(|l| l == "rpm = 60").unwrap() + 1;
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", &format!("line {line}"), "TOML"],
    );
}

#[test]
fn toml_unterminated_string_names_the_line() {
    let fx = Fixture::new();
    fx.edit_case("mode = \"drilling\"", "mode = \"drilling");
    let line = CASE.lines().position(|l| l == "mode = \"drilling\"").unwrap() + 1;
    fx.expect_error(&["survey", "case.toml"], &["case.toml", &format!("line {line}")]);
}

#[test]
fn force_unit_for_a_diameter() {
    let fx = Fixture::new();
    fx.edit_case("type = \"bit\"\nod = \"8.5 in\"", "type = \"bit\"\nod = \"8.5 kN\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[0].od`", "kN"]);
}

#[test]
fn unknown_unit_in_a_hole_diameter() {
    let fx = Fixture::new();
    fx.edit_case("diameter = \"8.5 in\"", "diameter = \"8.5 furlong\"");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`well.hole[1].diameter`", "furlong"],
    );
}

#[test]
fn wrong_type_for_a_quantity() {
    let fx = Fixture::new();
    fx.edit_case("rpm = 60", "rpm = true");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.rpm`"]);
}

#[test]
fn unknown_mode() {
    let fx = Fixture::new();
    fx.edit_case("mode = \"drilling\"", "mode = \"reaming\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.mode`", "reaming"]);
}

#[test]
fn unknown_component_type() {
    let fx = Fixture::new();
    fx.edit_case("type = \"collar\"", "type = \"colar\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[2].type`", "colar"]);
}

#[test]
fn stabilizer_without_body_od() {
    let fx = Fixture::new();
    fx.edit_case("body_od = \"6.5 in\"\n", "");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[1].body_od`"]);
}

#[test]
fn wob_and_hook_load_both_given() {
    let fx = Fixture::new();
    fx.edit_case("wob = \"100 kN\"", "wob = \"100 kN\"\nhook_load = \"900 kN\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.hook_load`", "wob"]);
}

#[test]
fn bit_md_below_the_survey() {
    let fx = Fixture::new();
    fx.edit_case("bit_md = \"1000 m\"", "bit_md = \"1200 m\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.bit_md`", "1200"]);
}

#[test]
fn bit_md_below_the_deepest_hole_section() {
    let fx = Fixture::new();
    fx.edit_case("to_md = \"1000 m\"", "to_md = \"900 m\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.bit_md`", "900"]);
}

#[test]
fn hole_sections_not_top_down() {
    let fx = Fixture::new();
    fx.edit_case("to_md = \"1000 m\"", "to_md = \"400 m\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`well.hole[1].to_md`"]);
}

#[test]
fn friction_out_of_range() {
    let fx = Fixture::new();
    fx.edit_case("friction = 0.2", "friction = 2.5");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`well.hole[0].friction`", "2.5"],
    );
}

#[test]
fn missing_well_table() {
    let fx = Fixture::new();
    fx.write("case.toml", "name = \"no well\"\n[mud]\ndensity = 1.2\n");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`well`"]);
}

#[test]
fn origin_with_two_values() {
    let fx = Fixture::new();
    fx.edit_case("survey = \"survey.csv\"", "survey = \"survey.csv\"\norigin = [1, 2]");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`well.origin`"]);
}

#[test]
fn out_is_a_directory() {
    let fx = Fixture::new();
    std::fs::create_dir(fx.path().join("outdir")).unwrap();
    let r = fx.run(&["survey", "case.toml", "--out", "outdir"]);
    check_error(&r, &["outdir"]);
}

// ---------------------------------------------------------------------------------------------
// Problems found by probing with bad input, each fixed and kept as a test.

#[test]
fn typo_of_a_required_key_is_named() {
    let fx = Fixture::new();
    fx.edit_case("type = \"collar\"\nod = ", "type = \"collar\"\nodd = ");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[2].odd`"]);
}

#[test]
fn survey_reversal_names_the_line() {
    let fx = Fixture::new();
    fx.write("survey.csv", "md,inc,azi\n0,0,0\n10,180,0\n20,0,0\n");
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv", "line 3"]);
}

#[test]
fn origin_with_a_comma_inside_a_string_is_rejected() {
    let fx = Fixture::new();
    fx.edit_case(
        "survey = \"survey.csv\"",
        "survey = \"survey.csv\"\norigin = [\"1,2\", 3]",
    );
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`well.origin`"]);
}

#[test]
fn survey_reversal_is_rejected() {
    // A 180 deg dogleg between two stations has no minimum-curvature arc.
    let fx = Fixture::new();
    fx.write("survey.csv", "md,inc,azi\n0,0,0\n10,180,0\n20,0,0\n");
    fx.expect_error(&["survey", "survey.csv"], &["survey.csv"]);
}

// ---------------------------------------------------------------------------------------------
// Positive paths on the example wells.

#[test]
fn survey_of_the_j_shape_case_prints_the_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let case = example_case("j-shape");
    let r = run_in(tmp.path(), &["survey", case.to_str().unwrap()]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert!(r.stderr.trim().is_empty(), "{}", r.describe());
    for s in [
        "survey: J-shape, 8.5 in section, fulcrum BHA",
        "stations: 88, MD 0.00 m to 2600.00 m",
        "total depth: 2600.00 m MD",
        "max DLS: 2.50 deg/30m",
        "final position: north",
    ] {
        assert!(r.stdout.contains(s), "missing `{s}`\n{}", r.describe());
    }
}

#[test]
fn survey_out_writes_the_interface_csv() {
    let tmp = tempfile::tempdir().unwrap();
    let case = example_case("j-shape");
    let r = run_in(
        tmp.path(),
        &["survey", case.to_str().unwrap(), "--out", "positions.csv"],
    );
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert!(r.stdout.contains("wrote positions.csv"), "{}", r.describe());
    let csv = std::fs::read_to_string(tmp.path().join("positions.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some(SURVEY_HEADER));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|f| f.parse::<f64>().expect(l)).collect())
        .collect();
    assert_eq!(rows.len(), 88);
    assert!(rows.iter().all(|r| r.len() == 7));
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[87][0] - 2600.0).abs() < 1e-9);
    assert!(rows.windows(2).all(|w| w[1][0] > w[0][0]), "MD must increase");
    // no stray temporary files next to the output
    let names: Vec<String> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["positions.csv".to_string()]);
}

#[test]
fn survey_of_the_forge_case_notes_the_assumed_feet() {
    let tmp = tempfile::tempdir().unwrap();
    let case = example_case("forge-16a");
    let r = run_in(tmp.path(), &["survey", case.to_str().unwrap()]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    let note = r
        .stdout
        .lines()
        .find(|l| l.contains("note:") && l.contains("assumed ft"))
        .unwrap_or_else(|| panic!("no `assumed ft` note\n{}", r.describe()));
    assert!(note.contains("Measured depth"), "{note}");
    // 10,955 ft = 3339.08 m
    assert!(r.stdout.contains("3339.08 m"), "{}", r.describe());
}

#[test]
fn survey_directly_on_a_csv_matches_the_case() {
    let tmp = tempfile::tempdir().unwrap();
    let csv = example_dir("j-shape").join("survey.csv");
    let case = example_case("j-shape");
    let r = run_in(tmp.path(), &["survey", csv.to_str().unwrap(), "--out", "from_csv.csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert!(r.stdout.contains("stations: 88"), "{}", r.describe());
    let r = run_in(
        tmp.path(),
        &["survey", case.to_str().unwrap(), "--out", "from_case.csv"],
    );
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    let a = std::fs::read_to_string(tmp.path().join("from_csv.csv")).unwrap();
    let b = std::fs::read_to_string(tmp.path().join("from_case.csv")).unwrap();
    assert_eq!(a, b);
}

#[test]
fn survey_csv_flag_prints_the_table() {
    let tmp = tempfile::tempdir().unwrap();
    let csv = example_dir("j-shape").join("survey.csv");
    let r = run_in(tmp.path(), &["survey", csv.to_str().unwrap(), "--csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    assert_eq!(r.stdout.lines().next(), Some(SURVEY_HEADER));
    assert_eq!(r.stdout.lines().count(), 89);
}

#[test]
fn survey_md_unit_option_reads_feet() {
    let fx = Fixture::new();
    fx.write("survey.csv", "md,inc,azi\n0,0,0\n1000,0,0\n");
    let r = fx.run(&["survey", "survey.csv", "--md-unit", "ft", "--csv"]);
    assert_eq!(r.code(), Some(0), "{}", r.describe());
    let last = r.stdout.lines().last().unwrap();
    assert!(last.starts_with("304.800,"), "{last}");
}

// ---------------------------------------------------------------------------------------------
// A solve that does not converge says so in one line, with the soft string's physical hints.

/// Sliding 250 kN onto the bit at the end of a 300 m lateral (300 m vertical, 90 deg build of
/// 450 m, 5 in pipe, friction 0.25): the soft string needs the top pushed down (hook load < 0,
/// lock-up, src/models/diagnose.rs) and buckles the pipe helically. With 3 iterations allowed the
/// stiff solve stops unconverged: exit non-zero, one `error:` line naming the non-convergence,
/// `--allow-unconverged`, the lock-up and the helical buckling; no output directory.
#[test]
fn unconverged_solve_names_lock_up_and_buckling() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("s.csv"),
        "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n750,90,0\n1050,90,0\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("c.toml"),
        format!(
            r#"[well]
survey = "s.csv"
hole = [{{ to_md = "1050 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
bit_md = "1050 m"
wob = "250 kN"
friction = 0.25
{DRILL_PIPE_BODY}[solver]
max_iterations = 3
"#
        ),
    )
    .unwrap();
    let r = run_in(dir.path(), &["solve", "c.toml", "--out", "out"]);
    check_error(
        &r,
        &[
            "c.toml",
            "did not converge",
            "--allow-unconverged",
            "lock-up",
            "helically buckled",
        ],
    );
    assert!(!dir.path().join("out").exists(), "no output on a failed solve");
}

// ---------------------------------------------------------------------------------------------
// Survey assimilation settings (`[tracking]`): a bad value names its key.

/// The fixture with a `[tracking]` table holding `line`.
fn with_tracking(line: &str) -> Fixture {
    let fx = Fixture::new();
    fx.edit_case("[solver]", &format!("[tracking]\n{line}\n\n[solver]"));
    fx
}

#[test]
fn tracking_negative_window() {
    with_tracking("window = \"-10 m\"")
        .expect_error(&["survey", "case.toml"], &["case.toml", "`tracking.window`", "-10"]);
}

#[test]
fn tracking_window_longer_than_the_survey() {
    with_tracking("window = \"5000 m\"").expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`tracking.window`", "longer than the survey"],
    );
}

#[test]
fn tracking_zero_or_negative_survey_noise() {
    with_tracking("survey_noise_inc = \"0 deg\"").expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`tracking.survey_noise_inc`", "positive"],
    );
    with_tracking("survey_noise_azi = -0.3").expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`tracking.survey_noise_azi`", "positive"],
    );
}

#[test]
fn tracking_unknown_parameter_and_key() {
    with_tracking("estimate = [\"walk_angle\", \"beta\"]")
        .expect_error(&["survey", "case.toml"], &["case.toml", "`tracking.estimate`", "beta"]);
    with_tracking("forgeting_length = \"300 m\"").expect_error(
        &["survey", "case.toml"],
        &["case.toml", "tracking", "forgeting_length", "forgetting_length"],
    );
}

// ---------------------------------------------------------------------------------------------
// Bent motors (docs/guide.md, `[[string]]` `bend_angle`, `bend_to_bit`; `[operation] toolface`).

#[test]
fn a_valid_bent_motor_is_accepted() {
    let fx = Fixture::new();
    fx.edit_case(
        "type = \"collar\"",
        "type = \"motor\"\nbend_angle = \"1.5 deg\"\nbend_to_bit = \"3 m\"",
    );
    let r = fx.run(&["survey", "case.toml"]);
    assert!(r.success(), "{}", r.describe());
}

#[test]
fn bend_angle_above_4_deg() {
    let fx = Fixture::new();
    fx.edit_case(
        "type = \"collar\"",
        "type = \"motor\"\nbend_angle = 4.5\nbend_to_bit = \"3 m\"",
    );
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[2].bend_angle`", "outside [0, 4] deg"],
    );
}

#[test]
fn negative_bend_angle() {
    let fx = Fixture::new();
    fx.edit_case(
        "type = \"collar\"",
        "type = \"motor\"\nbend_angle = -1\nbend_to_bit = \"3 m\"",
    );
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`string[2].bend_angle`"]);
}

#[test]
fn bend_outside_its_motor() {
    let fx = Fixture::new();
    fx.edit_case(
        "type = \"collar\"",
        "type = \"motor\"\nbend_angle = 1.5\nbend_to_bit = \"0.5 m\"",
    );
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[2].bend_to_bit`", "not on this motor"],
    );
}

#[test]
fn bend_on_a_component_that_is_not_a_motor() {
    let fx = Fixture::new();
    fx.edit_case(
        "type = \"collar\"",
        "type = \"collar\"\nbend_angle = 1.5\nbend_to_bit = \"3 m\"",
    );
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[2].bend_angle`", "only a `motor`"],
    );
}

#[test]
fn bend_angle_without_bend_to_bit() {
    let fx = Fixture::new();
    fx.edit_case("type = \"collar\"", "type = \"motor\"\nbend_angle = 1.5");
    fx.expect_error(
        &["survey", "case.toml"],
        &["case.toml", "`string[2].bend_to_bit`", "missing"],
    );
}

#[test]
fn toolface_that_is_not_an_angle() {
    let fx = Fixture::new();
    fx.edit_case("rpm = 60", "rpm = 60\ntoolface = \"90 m\"");
    fx.expect_error(&["survey", "case.toml"], &["case.toml", "`operation.toolface`"]);
}

// ---------------------------------------------------------------------------------------------
// Rotary steerable systems (docs/guide.md, `[[string]]` `rss_type`, `pad_force`, `pad_position`,
// `deflection_angle`, `hinge_position`, `ratio`; `[[steering]]` `ratio`).

#[test]
fn a_valid_rss_of_each_kind_is_accepted() {
    for keys in [
        "rss_type = \"push-the-bit\"\npad_force = \"15 kN\"\npad_position = \"3 m\"\nratio = 0.5",
        "rss_type = \"point-the-bit\"\ndeflection_angle = \"0.6 deg\"\nhinge_position = \"3 m\"",
    ] {
        let fx = Fixture::new();
        fx.edit_case("type = \"collar\"", &format!("type = \"rss\"\n{keys}"));
        let r = fx.run(&["survey", "case.toml"]);
        assert!(r.success(), "{}", r.describe());
    }
}

#[test]
fn bad_rss_keys_are_named() {
    let cases: [(&str, &[&str]); 9] = [
        (
            "type = \"rss\"\nrss_type = \"push-the-bit\"\npad_force = \"15 kN\"",
            &["`string[2].pad_position`", "pad_force without pad_position"],
        ),
        (
            "type = \"rss\"\nrss_type = \"push-the-bit\"\npad_force = \"15 kN\"\npad_position = \"3 m\"\ndeflection_angle = 0.5",
            &["`string[2].deflection_angle`", "this one is push-the-bit"],
        ),
        (
            "type = \"rss\"\nrss_type = \"point-the-bit\"\ndeflection_angle = 0.5\nhinge_position = \"3 m\"\npad_force = 10",
            &["`string[2].pad_force`", "this one is point-the-bit"],
        ),
        (
            "type = \"rss\"\nrss_type = \"push-the-bit\"\npad_force = \"15 kN\"\npad_position = \"3 m\"\nratio = 1.5",
            &["`string[2].ratio`", "outside [0, 1]"],
        ),
        (
            "type = \"rss\"\nrss_type = \"point-the-bit\"\ndeflection_angle = 4.5\nhinge_position = \"3 m\"",
            &["`string[2].deflection_angle`", "above the largest accepted, 4 deg"],
        ),
        (
            "type = \"rss\"\nrss_type = \"push-the-bit\"\npad_force = \"15 kN\"\npad_position = \"0.1 m\"",
            &["`string[2].pad_position`", "not on this rss"],
        ),
        ("type = \"rss\"\npad_force = \"15 kN\"", &["`string[2].rss_type`", "missing rss_type"]),
        ("type = \"rss\"\nrss_type = \"pull-the-bit\"", &["`string[2].rss_type`", "pull-the-bit"]),
        ("type = \"collar\"\npad_force = \"15 kN\"", &["`string[2].pad_force`", "only an `rss`"]),
    ];
    for (keys, expect) in cases {
        let fx = Fixture::new();
        fx.edit_case("type = \"collar\"", keys);
        let mut want = vec!["case.toml"];
        want.extend_from_slice(expect);
        fx.expect_error(&["survey", "case.toml"], &want);
    }
}
