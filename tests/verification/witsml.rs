//! WITSML 1.4.1.1 trajectories (`drillpath::io::witsml`) against the service companies' own
//! positions in the real Volve files, against the CSV extracted from the same file, and
//! against hostile XML.
//!
//! The data files are in `$CARGO_MANIFEST_DIR/../shared/data/volve-witsml/`; if one is absent
//! the test prints a note and returns. Run with
//! `cargo test --release --test verification witsml:: -- --nocapture` for the numbers.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use drillpath::case::{AzimuthReference, SurveyFile};
use drillpath::geometry::{Vec3, WellPath};
use drillpath::io::survey::{parse_survey, read_survey, SurveyUnits};
use drillpath::io::witsml::MAX_XML_BYTES;

/// Path of a file of the shared data directory, if present: beside the repository
/// (`../shared/data`), or beside the folder of a git worktree (`../../shared/data`).
fn volve(name: &str) -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let found = ["../shared/data", "../../shared/data"]
        .iter()
        .map(|d| root.join(d).join(name))
        .find(|p| p.is_file());
    if found.is_none() {
        println!("NOTE: {name} is absent from ../shared/data: test skipped");
    }
    found
}

/// The file's own `[md, tvd, dispNs, dispEw]` of every station, SI, read independently of
/// drillpath's reader (roxmltree directly, `m` only, as in the Volve files).
fn file_positions(path: &Path) -> Vec<[f64; 4]> {
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let value = |st: roxmltree::Node, name: &str| -> f64 {
        let el = st.children().find(|c| c.tag_name().name() == name).unwrap();
        assert_eq!(el.attribute("uom"), Some("m"), "{name}");
        el.text().unwrap().trim().parse().unwrap()
    };
    doc.descendants()
        .filter(|n| n.tag_name().name() == "trajectoryStation")
        .map(|st| {
            [
                value(st, "md"),
                value(st, "tvd"),
                value(st, "dispNs"),
                value(st, "dispEw"),
            ]
        })
        .collect()
}

fn read(path: &Path) -> SurveyFile {
    read_survey(path, &SurveyUnits::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Minimum curvature from the tie-in position the file gives, against the file's own positions.
fn positions_match(name: &str, stations: usize) -> Option<SurveyFile> {
    let path = volve(name)?;
    let file = read(&path);
    assert_eq!(file.survey.len(), stations);
    let o = file.origin.expect("the tie-in position");
    let w = WellPath::new(&file.survey, Vec3::new(o[0], o[1], o[2])).unwrap();
    let expected = file_positions(&path);
    assert_eq!(expected.len(), stations);
    let mut worst = (0.0_f64, 0.0);
    for (k, [md, tvd, n, e]) in expected.iter().enumerate() {
        assert_eq!(w.stations()[k].md_m, *md);
        let p = w.station_position(k);
        for d in [p.z - tvd, p.x - n, p.y - e] {
            if d.abs() > worst.0 {
                worst = (d.abs(), *md);
            }
        }
    }
    println!(
        "{name}: largest difference from the file's tvd/dispNs/dispEw {:.2} mm at MD {:.2} m",
        worst.0 * 1e3,
        worst.1
    );
    assert!(worst.0 < 0.005, "{name}: {:.2} mm at MD {} m", worst.0 * 1e3, worst.1);
    Some(file)
}

#[test]
fn f9a_in_radians_matches_the_files_positions() {
    // Reference: Baker Hughes' own tvd/dispNs/dispEw in the file (angles in rad), 5 mm.
    let Some(f) = positions_match("volve-witsml/15_9-F-9A_2016_trajectory_bhi.xml", 25) else {
        return;
    };
    assert_eq!(f.azimuth_reference, AzimuthReference::True);
    assert_eq!((f.md_unit.as_str(), f.inc_unit.as_str()), ("m", "rad"));
    assert_eq!(f.station_info[0].kind, "tie in point");
    assert_eq!(f.station_info[1].kind, "gyro north seeking");
}

#[test]
fn f5_in_degrees_matches_the_files_positions_and_its_csv() {
    // Reference: Schlumberger's own positions (5 mm), and the CSV extracted verbatim from the
    // same file: identical stations, bit for bit.
    let Some(f) = positions_match("volve-witsml/15_9-F-5_trajectory_slb.xml", 38) else {
        return;
    };
    assert_eq!(f.azimuth_reference, AzimuthReference::Grid);
    assert!((f.magnetic_declination_rad.unwrap().to_degrees() + 2.21).abs() < 1e-12);
    assert!((f.grid_convergence_rad.unwrap().to_degrees() + 0.95).abs() < 1e-12);
    assert!(
        f.azimuth_reference_source.contains("gridCorUsed -0.95 deg"),
        "{}",
        f.azimuth_reference_source
    );
    let tf = f
        .station_info
        .iter()
        .filter(|s| s.gtf_rad.is_some() && s.mtf_rad.is_some())
        .count();
    assert_eq!(tf, 33, "toolfaces on 33 of the 38 stations (SOURCE.md)");
    assert!((f.station_info[1].gtf_rad.unwrap().to_degrees() + 162.474).abs() < 1e-9);
    assert!((f.station_info[1].mtf_rad.unwrap().to_degrees() - 19.542).abs() < 1e-9);
    let kinds = |k: &str| f.station_info.iter().filter(|s| s.kind == k).count();
    assert_eq!(
        (kinds("tie in point"), kinds("magnetic MWD"), kinds("gyro MWD")),
        (1, 32, 5)
    );
    let Some(csv) = volve("volve-15_9-F-5/15_9-F-5_actual_trajectory_17.5in.csv") else {
        return;
    };
    let c = read(&csv);
    assert_eq!(
        c.survey.stations(),
        f.survey.stations(),
        "the XML and its CSV give the same stations"
    );
}

#[test]
fn f4_without_azimuths_is_refused_naming_them() {
    let Some(path) = volve("volve-witsml/15_9-F-4_2008_trajectory_slb.xml") else {
        return;
    };
    let e = read_survey(&path, &SurveyUnits::default()).unwrap_err().to_string();
    println!("{e}");
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(e.contains("element `azi` of station `S-0`"), "{e}");
    assert!(e.contains("67 of the 68 stations have no `azi` element"), "{e}");
    assert!(e.contains("`S-1459001400` (MD 145.90014 m, line 74)"), "{e}");
    assert!(e.contains("never takes a missing azimuth as 0"), "{e}");
}

/// A trajectory file: `trajectories` is the inside of `<trajectorys>`.
fn doc(trajectories: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<trajectorys xmlns="http://www.witsml.org/schemas/1series" version="1.4.1.1">
{trajectories}
</trajectorys>
"#
    )
}

/// A trajectory named `name` with uid `uid` and `stations` (its `trajectoryStation`s).
fn trajectory(name: &str, uid: &str, stations: &str) -> String {
    format!(
        r#"<trajectory uidWell="W" uidWellbore="B" uid="{uid}"><nameWell>w</nameWell><nameWellbore>wb</nameWellbore><name>{name}</name>
<aziRef>true north</aziRef>
{stations}
</trajectory>"#
    )
}

/// A station: `md` in ft, angles in dega, of type `kind`.
fn station(uid: &str, kind: &str, md_ft: f64, incl: f64, azi: f64) -> String {
    format!(
        r#"<trajectoryStation uid="{uid}"><typeTrajStation>{kind}</typeTrajStation><md uom="ft">{md_ft}</md><incl uom="dega">{incl}</incl><azi uom="dega">{azi}</azi><gtf uom="dega">45</gtf></trajectoryStation>
"#
    )
}

fn parse(text: &str, trajectory: Option<&str>) -> Result<SurveyFile, String> {
    let units = SurveyUnits {
        trajectory: trajectory.map(str::to_string),
        ..Default::default()
    };
    parse_survey(text.as_bytes(), Path::new("t.xml"), &units).map_err(|e| e.to_string())
}

fn three_stations() -> String {
    [
        station("a", "tie in point", 0.0, 0.0, 0.0),
        station("b", "magnetic MWD", 1000.0, 10.0, 90.0),
        station("c", "magnetic MWD", 2000.0, 20.0, 95.0),
    ]
    .concat()
}

#[test]
fn feet_degrees_types_and_toolfaces() {
    let s = [three_stations(), station("p", "hold to MD", 2500.0, 20.0, 95.0)].concat();
    let f = parse(&doc(&trajectory("plan", "T1", &s)), None).unwrap();
    assert_eq!(f.survey.len(), 3, "the projected station is not a measurement");
    assert_eq!(f.projected.len(), 1);
    assert_eq!(f.projected[0].1.kind, "hold to MD");
    assert!((f.projected[0].0.md_m - 762.0).abs() < 1e-9);
    assert!((f.survey.stations()[1].md_m - 304.8).abs() < 1e-12);
    assert!((f.survey.stations()[2].inc_rad - 20f64.to_radians()).abs() < 1e-15);
    assert_eq!(f.md_unit, "ft");
    assert!((f.station_info[2].gtf_rad.unwrap() - 45f64.to_radians()).abs() < 1e-15);
    assert!(
        f.notes
            .iter()
            .any(|n| n.contains("not measurements") && n.contains("`p` (hold to MD")),
        "{:?}",
        f.notes
    );
}

#[test]
fn several_trajectories_are_chosen_by_name_or_uid() {
    let text = doc(&[
        trajectory("MWD run 1", "T1", &three_stations()),
        trajectory("Gyro", "T2", &three_stations()),
    ]
    .concat());
    let e = parse(&text, None).unwrap_err();
    assert!(
        e.contains("holds 2 `trajectory` objects: `MWD run 1` (uid `T1`), `Gyro` (uid `T2`)"),
        "{e}"
    );
    assert!(e.starts_with("t.xml: line 2, root element `trajectorys`"), "{e}");
    assert!(parse(&text, Some("Gyro")).is_ok());
    assert!(parse(&text, Some("T1")).is_ok());
    let e = parse(&text, Some("T3")).unwrap_err();
    assert!(
        e.contains("no `trajectory` named or with uid `T3`") && e.contains("`Gyro` (uid `T2`)"),
        "{e}"
    );
}

#[test]
fn units_are_required_and_known() {
    let t = |st: &str| {
        doc(&trajectory(
            "t",
            "T",
            &format!("{}{st}", station("a", "tie in point", 0.0, 0.0, 0.0)),
        ))
    };
    let e = parse(&t(r#"<trajectoryStation uid="b"><md uom="m">10</md><incl>1</incl><azi uom="dega">2</azi></trajectoryStation>"#), None).unwrap_err();
    assert!(
        e.contains("element `incl` of station `b` (MD 10 m): no `uom` attribute"),
        "{e}"
    );
    let e = parse(&t(r#"<trajectoryStation uid="b"><md uom="m">10</md><incl uom="deg">1</incl><azi uom="dega">2</azi></trajectoryStation>"#), None).unwrap_err();
    assert!(e.contains("unknown uom `deg`") && e.contains("`dega`, `rad`"), "{e}");
    let e = parse(&t(r#"<trajectoryStation uid="b"><md uom="dega">10</md><incl uom="dega">1</incl><azi uom="dega">2</azi></trajectoryStation>"#), None).unwrap_err();
    assert!(
        e.contains("element `md` of station `b`") && e.contains("is a angle unit"),
        "{e}"
    );
    let e = parse(&t(r#"<trajectoryStation uid="b"><md uom="m">ten</md><incl uom="dega">1</incl><azi uom="dega">2</azi></trajectoryStation>"#), None).unwrap_err();
    assert!(e.contains("`ten` is not a number"), "{e}");
    let e = parse(&t(r#"<trajectoryStation uid="b"><md uom="m">0</md><incl uom="dega">1</incl><azi uom="dega">2</azi></trajectoryStation>"#), None).unwrap_err();
    assert!(
        e.contains("station `b` (MD 0 m)") && e.contains("not greater than 0 ft of the station before it (`a`"),
        "{e}"
    );
    let e = parse(
        &t(r#"<trajectoryStation uid="b"><md uom="m">10</md><azi uom="dega">2</azi></trajectoryStation>"#),
        None,
    )
    .unwrap_err();
    assert!(
        e.contains("element `incl` of station `b`") && e.contains("1 of the 2 stations have no `incl`"),
        "{e}"
    );
}

/// `text` is refused by the reader, fast, with an error naming `t.xml` and containing `what`.
fn refused(text: &[u8], what: &str) -> String {
    let t0 = Instant::now();
    let r = parse_survey(text, Path::new("t.xml"), &SurveyUnits::default());
    let dt = t0.elapsed();
    let e = r.map(|_| ()).unwrap_err().to_string();
    assert!(dt < Duration::from_secs(1), "{:.2} s for: {e}", dt.as_secs_f64());
    assert!(e.starts_with("t.xml"), "{e}");
    assert!(e.contains(what), "expected `{what}` in: {e}");
    e
}

#[test]
fn hostile_xml_is_refused() {
    // an external entity: never resolved (the DTD itself is refused)
    let secret = std::env::temp_dir().join("drillpath-witsml-secret.txt");
    std::fs::write(&secret, "TOPSECRET").unwrap();
    let xxe = format!(
        r#"<?xml version="1.0"?><!DOCTYPE trajectorys [<!ENTITY x SYSTEM "file://{}">]>
<trajectorys xmlns="http://www.witsml.org/schemas/1series" version="1.4.1.1"><trajectory uid="T"><name>&x;</name></trajectory></trajectorys>"#,
        secret.display()
    );
    let e = refused(xxe.as_bytes(), "document type declaration");
    assert!(!e.contains("TOPSECRET"), "{e}");
    // billion laughs: answered at once, nothing expanded
    let mut laughs = String::from("<?xml version=\"1.0\"?><!DOCTYPE lolz [<!ENTITY lol \"lol\">");
    for k in 1..10 {
        let prev = if k == 1 {
            "lol".to_string()
        } else {
            format!("lol{}", k - 1)
        };
        laughs += &format!("<!ENTITY lol{k} \"{}\">", format!("&{prev};").repeat(10));
    }
    laughs += "]><trajectorys>&lol9;</trajectorys>";
    refused(laughs.as_bytes(), "document type declaration");
    // truncated, malformed, wrong root, not UTF-8
    let good = doc(&trajectory("t", "T", &three_stations()));
    assert!(parse(&good, None).is_ok());
    let cut = &good.as_bytes()[..good.len() * 2 / 3];
    refused(cut, "truncated");
    refused(good.replace("</md>", "</mdx>").as_bytes(), "not well-formed XML");
    let e = refused(
        b"<?xml version=\"1.0\"?>\n<wells xmlns=\"http://www.witsml.org/schemas/1series\"/>",
        "root element `wells`",
    );
    assert!(
        e.contains("line 2") && e.contains("not a WITSML 1.4.1.1 `trajectorys` file"),
        "{e}"
    );
    refused(
        good.replace("version=\"1.4.1.1\"", "version=\"1.3.1.1\"").as_bytes(),
        "version `1.3.1.1`",
    );
    refused(
        b"<trajectorys xmlns=\"http://www.energistics.org/energyml/data/witsmlv2\"/>",
        "WITSML 2.x objects are not read",
    );
    let mut latin1 = good.clone().into_bytes();
    latin1.extend_from_slice(b"<!-- \xe9 -->");
    refused(&latin1, "not UTF-8");
    refused(doc("").as_bytes(), "holds no `trajectory` object");
    // an error just past the last line end names the last line (found by the fuzz test)
    let e = refused(b"<?xml version=\"1.0\"\n", "not well-formed XML");
    assert!(e.starts_with("t.xml: line 1:"), "{e}");
    // a value that overflows in SI units, or lies beyond any physical size
    let t = doc(&trajectory(
        "t",
        "T",
        &three_stations().replace("<md uom=\"ft\">2000</md>", "<md uom=\"km\">1e306</md>"),
    ));
    refused(t.as_bytes(), "`1e306` is not a finite number of physical size");
    refused(doc(&trajectory("t", "T", "")).as_bytes(), "has no `trajectoryStation`");
}

#[test]
fn a_file_over_the_size_limit_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.xml");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(MAX_XML_BYTES + 1).unwrap(); // sparse: no disk used
    let t0 = Instant::now();
    let e = read_survey(&path, &SurveyUnits::default()).unwrap_err().to_string();
    assert!(t0.elapsed() < Duration::from_secs(1));
    assert!(
        e.starts_with(&path.display().to_string()) && e.contains("larger than 16 MiB"),
        "{e}"
    );
}

/// A case in a temporary directory reading the F-9 A trajectory, wbGeometry and tubular of the
/// Volve data set (`extra` added to `[well]`).
fn f9a_case(extra: &str) -> Option<(tempfile::TempDir, PathBuf)> {
    let traj = volve("volve-witsml/15_9-F-9A_2016_trajectory_bhi.xml")?;
    let geo = volve("volve-witsml/15_9-F-9A_2016_wbGeometry.xml")?;
    let tub = volve("volve-witsml/15_9-F-9A_2016_tubular_dp.xml")?;
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(
        &case,
        format!(
            "string_from = \"{}\"\n[well]\nsurvey = \"{}\"\nhole_from = \"{}\"\n{extra}\n[operation]\nmode = \"trip_out\"\nbit_md = \"886 m\"\n",
            tub.display(),
            traj.display(),
            geo.display()
        ),
    )
    .unwrap();
    Some((dir, case))
}

#[test]
fn f9a_wbgeometry_is_the_hole_and_its_tubular_the_string() {
    // Reference: the file's five sections (listed out of order), by hand: riser 0-20 and
    // 20-139 m (ID 0.31242 m), casing 139-397 m (0.31496 m) and 397-941 m (0.216789 m), open
    // hole 941-1206 m (0.168275 m); cased sections with the case's cased_friction.
    let Some((_dir, case)) = f9a_case("cased_friction = 0.2") else {
        return;
    };
    let c = drillpath::io::case_toml::load_case(&case, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let got: Vec<(f64, f64, Option<f64>)> = c
        .well
        .hole
        .sections()
        .iter()
        .map(|s| (s.to_md_m, s.diameter_m, s.friction))
        .collect();
    let expected = [
        (20.0, 0.312420000000456, Some(0.2)),
        (139.0, 0.312420000000456, Some(0.2)),
        (397.0, 0.31496000000046, Some(0.2)),
        (941.0, 0.216789000000317, Some(0.2)),
        (1206.0, 0.168275000000246, None),
    ];
    assert_eq!(got, expected);
    assert_eq!(c.string.components.len(), 1);
    assert!((c.string.components[0].length_m - 886.0).abs() < 1e-9);
    assert!((c.string.components[0].body_od_m - 0.1397).abs() < 1e-9);
    assert!(c
        .input_files()
        .iter()
        .any(|p| p.ends_with("15_9-F-9A_2016_wbGeometry.xml")));
    assert!(c
        .input_files()
        .iter()
        .any(|p| p.ends_with("15_9-F-9A_2016_tubular_dp.xml")));
    let Some((_dir, case)) = f9a_case("hole = [{ to_md = 1206, diameter = 8.5 }]") else {
        return;
    };
    let e = drillpath::io::case_toml::load_case(&case, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("key `well.hole_from`") && e.contains("give one of them"),
        "{e}"
    );
}

#[test]
fn wbgeometry_gaps_and_missing_diameters_are_refused() {
    let sec = |uid: &str, kind: &str, top: f64, bottom: f64, id: &str| {
        format!("<wbGeometrySection uid=\"{uid}\"><typeHoleCasing>{kind}</typeHoleCasing><mdTop uom=\"m\">{top}</mdTop><mdBottom uom=\"m\">{bottom}</mdBottom>{id}</wbGeometrySection>\n")
    };
    let doc = |body: String| {
        format!("<?xml version=\"1.0\"?>\n<wbGeometrys xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n<wbGeometry uid=\"G\"><name>g</name>\n{body}</wbGeometry>\n</wbGeometrys>\n")
    };
    let parse = |t: &str| {
        drillpath::io::witsml::geometry::parse_geometry(t, Path::new("g.xml"), None).map_err(|e| e.to_string())
    };
    let id = |v: f64| format!("<idSection uom=\"in\">{v}</idSection>");
    let ok = doc([
        sec("b", "open hole", 500.0, 900.0, &id(8.5)),
        sec("a", "casing", 0.0, 500.0, &id(8.835)),
    ]
    .concat());
    let s = parse(&ok).unwrap();
    assert_eq!((s[0].uid.as_str(), s[1].uid.as_str()), ("a", "b"));
    assert!((s[1].id_m - 8.5 * 0.0254).abs() < 1e-15);
    let e = parse(&doc([
        sec("a", "casing", 0.0, 500.0, &id(8.835)),
        sec("b", "open hole", 520.0, 900.0, &id(8.5)),
    ]
    .concat()))
    .unwrap_err();
    assert!(
        e.contains("section `b` (open hole): a gap between it (mdTop 520 m) and section `a`"),
        "{e}"
    );
    let e = parse(&doc([
        sec("a", "casing", 0.0, 500.0, ""),
        sec("b", "open hole", 500.0, 900.0, &id(8.5)),
    ]
    .concat()))
    .unwrap_err();
    assert!(
        e.contains("g.xml: line 4, section `a` (casing): has no `idSection` element"),
        "{e}"
    );
}

#[test]
fn roxmltree_itself_neither_fetches_nor_expands_without_bound() {
    // drillpath refuses any DTD before roxmltree expands anything; this checks the second line of
    // defence, roxmltree with DTDs allowed: an external entity is not fetched and nested
    // entities stop at its expansion limits, at once.
    let opts = || roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let secret = std::env::temp_dir().join("drillpath-witsml-secret-2.txt");
    std::fs::write(&secret, "TOPSECRET").unwrap();
    let xxe = format!(
        "<!DOCTYPE r [<!ENTITY x SYSTEM \"file://{}\">]><r>&x;</r>",
        secret.display()
    );
    match roxmltree::Document::parse_with_options(&xxe, opts()) {
        Ok(d) => assert!(!d.root_element().text().unwrap_or("").contains("TOPSECRET")),
        Err(e) => assert!(!e.to_string().contains("TOPSECRET")),
    }
    let mut lol = String::from("<!DOCTYPE r [<!ENTITY l0 \"lol\">");
    for k in 1..10 {
        lol += &format!("<!ENTITY l{k} \"{}\">", format!("&l{};", k - 1).repeat(10));
    }
    lol += "]><r>&l9;</r>";
    let t0 = Instant::now();
    let r = roxmltree::Document::parse_with_options(&lol, opts());
    assert!(t0.elapsed() < Duration::from_secs(1));
    assert!(r.is_err(), "10^9 expansions must not be built");
}
