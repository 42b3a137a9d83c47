//! A case whose string comes from a WITSML 1.4.1.1 `tubular` (`string_from = "FILE.xml"`),
//! written here from the schema (bit, stabilizers with blades, collars in mixed units, HWDP,
//! drill pipe; components listed out of `sequence` order), solves like the same case written
//! by hand (issue 22: within 0.1%); what drillpath cannot model is refused by uid.

use std::path::Path;

use crate::common::{assert_error_names, example_dir, run_in, run_ok};

/// One `tubularComponent`: `inner` is its elements after the type and sequence.
fn comp(uid: &str, kind: &str, seq: u32, inner: &str) -> String {
    format!("<tubularComponent uid=\"{uid}\"><typeTubularComp>{kind}</typeTubularComp><sequence>{seq}</sequence>{inner}</tubularComponent>\n")
}

/// The j-shape example's BHA and string as a WITSML tubular, components out of order, units
/// mixed (mm, in, m, ft; kg/m and lbm/ft).
fn tubular(extra: &str) -> String {
    let stab = |uid: &str, seq: u32, blade: &str| {
        comp(
            uid,
            if seq == 2 { "near bit stabilizer" } else { "stabilizer" },
            seq,
            &format!("<id uom=\"in\">2.8125</id><od uom=\"in\">6.5</od><len uom=\"m\">1.6</len><stabilizer uid=\"b{seq}\"><lenBlade uom=\"m\">0.4</lenBlade><odBladeMx uom=\"in\">{blade}</odBladeMx></stabilizer>"),
        )
    };
    let parts = [
        comp("dp", "drill pipe", 7, "<id uom=\"in\">4.276</id><od uom=\"in\">5</od><len uom=\"m\">2000</len><wtPerLen uom=\"kg/m\">33.6</wtPerLen><lenJointAv uom=\"m\">9.144</lenJointAv><grade>S-135</grade><connection uid=\"c\"><od uom=\"in\">6.625</od></connection>"),
        comp("dc1", "drill collar", 3, "<id uom=\"mm\">71.4375</id><od uom=\"in\">6.5</od><len uom=\"ft\">90.55118110236220</len>"),
        comp("bit", "bit", 1, "<od uom=\"mm\">215.9</od><len uom=\"m\">0.3</len>"),
        comp("dc2", "drill collar", 5, "<id uom=\"in\">2.8125</id><od uom=\"m\">0.1651</od><len uom=\"m\">27.6</len>"),
        stab("nbs", 2, "8.5"),
        comp("hw", "heavy weight drill pipe", 6, "<id uom=\"in\">3</id><od uom=\"in\">5</od><len uom=\"ft\">459.3175853018373</len><wtPerLen uom=\"lbm/ft\">49.3</wtPerLen><lenJointAv uom=\"ft\">30</lenJointAv><connection uid=\"c\"><od uom=\"in\">6.5</od></connection>"),
        stab("ss", 4, "8.4375"),
        extra.to_string(),
    ];
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<tubulars xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n<tubular uid=\"T1\"><name>rotary fulcrum BHA</name><typeTubularAssy>drilling</typeTubularAssy>\n{}</tubular>\n</tubulars>\n",
        parts.concat()
    )
}

/// The j-shape case in `dir` with its string replaced by `string` (TOML text).
fn write_case(dir: &Path, string: &str) {
    let text = std::fs::read_to_string(example_dir("j-shape").join("case.toml")).unwrap();
    let start = text.find("[[string]]").unwrap();
    let end = text.find("[bit_rock]").unwrap();
    let case = format!("{}{string}\n{}", &text[..start], &text[end..]);
    std::fs::write(dir.join("case.toml"), case).unwrap();
    std::fs::copy(example_dir("j-shape").join("survey.csv"), dir.join("survey.csv")).unwrap();
}

/// The same string by hand: the j-shape's, with blade diameters and lengths as keys.
const BY_HAND: &str = r#"
[[string]]
type = "bit"
od = "8.5 in"
length = "0.3 m"

[[string]]
type = "stabilizer"
od = "6.5 in"
blade_od = "8.5 in"
blade_length = "0.4 m"
id = "2.8125 in"
length = "1.6 m"

[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "27.6 m"

[[string]]
type = "stabilizer"
od = "6.5 in"
blade_od = "8.4375 in"
blade_length = "0.4 m"
id = "2.8125 in"
length = "1.6 m"

[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "27.6 m"

[[string]]
type = "hwdp"
od = "5 in"
id = "3 in"
length = "140 m"
weight = "49.3 lb/ft"
tool_joint_od = "6.5 in"
joint_length = "30 ft"

[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "33.6 kg/m"
tool_joint_od = "6.625 in"
joint_length = "30 ft"
grade = "S-135"
"#;

fn numbers(json: &str) -> Vec<(String, f64)> {
    let j: serde_json::Value = serde_json::from_str(json).unwrap();
    let mut out = Vec::new();
    for (group, keys) in [
        ("bit", &["build_force_kN", "walk_force_kN", "torque_kNm"][..]),
        ("surface", &["hook_load_kN", "torque_kNm"][..]),
    ] {
        for k in keys {
            let v = j[group][k].as_f64().unwrap_or_else(|| panic!("{group}.{k} in {j}"));
            out.push((format!("{group}.{k}"), v));
        }
    }
    out
}

#[test]
fn a_tubular_string_solves_like_the_case_written_by_hand() {
    let hand = tempfile::tempdir().unwrap();
    write_case(hand.path(), BY_HAND);
    let xml = tempfile::tempdir().unwrap();
    write_case(xml.path(), "string_from = \"bha.xml\"\n");
    // `string_from` is a top-level key: move it above the first table
    let case = std::fs::read_to_string(xml.path().join("case.toml")).unwrap();
    let case = format!(
        "string_from = \"bha.xml\"\n{}",
        case.replace("string_from = \"bha.xml\"\n", "")
    );
    std::fs::write(xml.path().join("case.toml"), case).unwrap();
    std::fs::write(xml.path().join("bha.xml"), tubular("")).unwrap();
    let a = run_ok(hand.path(), &["solve", "case.toml", "--json"]);
    let b = run_ok(xml.path(), &["solve", "case.toml", "--json"]);
    assert!(
        b.stderr.contains("out of `sequence` order") && b.stderr.contains("fills the string to the surface"),
        "{}",
        b.stderr
    );
    for ((k, x), (_, y)) in numbers(&a.stdout).iter().zip(numbers(&b.stdout)) {
        let rel = (x - y).abs() / x.abs().max(1e-9);
        println!("{k}: by hand {x}, from the tubular {y}, {:.2e}", rel);
        assert!(rel < 1e-3, "{k}: {x} against {y}");
    }
    // blades: the same with contact along the blades
    for dir in [hand.path(), xml.path()] {
        let c = std::fs::read_to_string(dir.join("case.toml")).unwrap();
        std::fs::write(
            dir.join("case.toml"),
            c.replace("[solver]", "[solver]\nstabilizer_contact = \"blade\""),
        )
        .unwrap();
    }
    let a = run_in(hand.path(), &["solve", "case.toml", "--json", "--fidelity", "bha"]);
    let b = run_in(xml.path(), &["solve", "case.toml", "--json", "--fidelity", "bha"]);
    assert_eq!(a.success(), b.success());
    if a.success() {
        let j = |s: &str| {
            serde_json::from_str::<serde_json::Value>(s).unwrap()["bit"]["build_force_kN"]
                .as_f64()
                .unwrap()
        };
        assert!(
            (j(&a.stdout) - j(&b.stdout)).abs() <= 1e-3 * j(&a.stdout).abs(),
            "blades"
        );
    }
    // the tubular is an input: refused as an output
    let before = std::fs::read(xml.path().join("bha.xml")).unwrap();
    let r = run_in(xml.path(), &["solve", "case.toml", "--report", "bha.xml"]);
    assert_eq!(r.code(), Some(2), "{}", r.describe());
    let last = r.stderr.lines().last().unwrap();
    assert!(
        last.starts_with("error: option `--report`: bha.xml is an input of this run"),
        "{}",
        r.stderr
    );
    assert_eq!(std::fs::read(xml.path().join("bha.xml")).unwrap(), before);
}

/// The case in a fresh directory with the tubular `xml` and case top keys `keys`.
fn refused(xml: &str, keys: &str, must: &[&str]) {
    let d = tempfile::tempdir().unwrap();
    write_case(d.path(), "");
    let case = std::fs::read_to_string(d.path().join("case.toml")).unwrap();
    std::fs::write(
        d.path().join("case.toml"),
        format!("string_from = \"bha.xml\"\n{keys}\n{case}"),
    )
    .unwrap();
    std::fs::write(d.path().join("bha.xml"), xml).unwrap();
    let r = run_in(d.path(), &["solve", "case.toml"]);
    assert_error_names(&r, must);
    assert_eq!(r.code(), Some(2));
}

#[test]
fn what_drillpath_cannot_model_is_refused_by_uid() {
    // a bend on a component that is not a motor
    let bent_sub = tubular("").replace(
        "<len uom=\"m\">27.6</len>",
        "<len uom=\"m\">27.6</len><bend uid=\"b\"><angle uom=\"dega\">1</angle><distBendBot uom=\"m\">1</distBendBot></bend>",
    );
    refused(&bent_sub, "", &["bha.xml: key `tubularComponent[dc2].bend_angle`"]);
    // a bend without its distance from the bottom
    let no_dist = tubular("")
        .replace("near bit stabilizer</typeTubularComp>", "mud motor</typeTubularComp>")
        .replace(
            "<stabilizer uid=\"b2\"><lenBlade uom=\"m\">0.4</lenBlade><odBladeMx uom=\"in\">8.5</odBladeMx></stabilizer>",
            "<bend uid=\"b\"><angle uom=\"dega\">1.5</angle></bend>",
        );
    refused(
        &no_dist,
        "",
        &["element `bend` of component `nbs` (mud motor)", "has no `distBendBot`"],
    );
    let spear = comp(
        "f1",
        "fishing spear",
        8,
        "<id uom=\"in\">2</id><od uom=\"in\">6</od><len uom=\"m\">2</len>",
    );
    refused(
        &tubular(&spear),
        "",
        &[
            "element `typeTubularComp` of component `f1` (fishing spear)",
            "no mechanical meaning",
            "string_other_as_tube",
        ],
    );
    let twice = comp(
        "x",
        "drill collar",
        3,
        "<id uom=\"in\">2.8125</id><od uom=\"in\">6.5</od><len uom=\"m\">9</len>",
    );
    refused(
        &tubular(&twice),
        "",
        &[
            "element `sequence` of component `x`",
            "sequence 3 is also that of component `dc1`",
        ],
    );
    let no_blade = tubular("").replace("<odBladeMx uom=\"in\">8.5</odBladeMx>", "");
    refused(
        &no_blade,
        "",
        &["element `stabilizer` of component `nbs`", "has no `odBladeMx`"],
    );
    let wide = tubular("").replace("<od uom=\"m\">0.1651</od>", "<od uom=\"m\">0.2651</od>");
    refused(
        &wide,
        "",
        &["bha.xml: key `tubularComponent[dc2].od`", "wider than the hole"],
    );
    let no_uom = tubular("").replace("<len uom=\"m\">27.6</len>", "<len>27.6</len>");
    refused(
        &no_uom,
        "",
        &["element `len` of component `dc2` (drill collar)", "no `uom` attribute"],
    );
    refused(
        &tubular(""),
        "[[string]]\ntype = \"bit\"\nod = \"8.5 in\"\nlength = 0.3\n",
        &["key `string_from`", "give one of them"],
    );
}

#[test]
fn an_unknown_component_may_be_read_as_a_tube_on_request() {
    let d = tempfile::tempdir().unwrap();
    write_case(d.path(), "");
    let case = std::fs::read_to_string(d.path().join("case.toml")).unwrap();
    std::fs::write(
        d.path().join("case.toml"),
        format!("string_from = \"bha.xml\"\nstring_other_as_tube = true\n{case}"),
    )
    .unwrap();
    let spear = comp(
        "f1",
        "other",
        8,
        "<id uom=\"in\">2</id><od uom=\"in\">6</od><len uom=\"m\">2</len>",
    );
    std::fs::write(d.path().join("bha.xml"), tubular(&spear)).unwrap();
    let r = run_ok(d.path(), &["solve", "case.toml"]);
    assert!(
        r.stderr
            .contains("component `f1` (other) has no mechanical meaning to drillpath: read as a plain tube"),
        "{}",
        r.stderr
    );
}

#[test]
fn import_writes_an_editable_case_that_solves_like_string_from() {
    let d = tempfile::tempdir().unwrap();
    let bent = comp("m1", "mud motor", 8, "<id uom=\"in\">3</id><od uom=\"in\">6.75</od><len uom=\"m\">8</len><bend uid=\"b\"><angle uom=\"dega\">1.5</angle><distBendBot uom=\"m\">2</distBendBot></bend>");
    std::fs::write(d.path().join("bent.xml"), tubular(&bent)).unwrap();
    std::fs::write(d.path().join("bha.xml"), tubular("")).unwrap();
    // the bent motor: written as the motor's bend keys, 2 m above the motor's bottom
    let r = run_ok(d.path(), &["import", "bent.xml", "--out", "bent.toml"]);
    assert!(r.stdout.contains("wrote bent.toml"), "{}", r.stdout);
    let text = std::fs::read_to_string(d.path().join("bent.toml")).unwrap();
    assert!(
        text.contains("[[string]]   # component `m1` (mud motor)\n# the motor's bent housing")
            && text.contains("(the components below + distBendBot)\ntype = \"motor\""),
        "{text}"
    );
    assert!(text.contains("bend_angle = \"1.5 deg\""), "{text}");
    // below the motor: bit 0.3, stabs 1.6 + 1.6, collars 27.6 + 27.6, HWDP 140, DP (its len 2000 m)
    assert!(text.contains("bend_to_bit = \"2200.7 m\""), "{text}");
    // the straight string: the imported tables in the j-shape case solve like string_from
    let r = run_ok(d.path(), &["import", "bha.xml", "--out", "case.toml"]);
    assert!(r.success());
    let imported = std::fs::read_to_string(d.path().join("case.toml")).unwrap();
    assert!(
        imported.contains("# The string from the bit upward")
            && imported.contains("# no length: fills the string to the surface (the file's len is 2000 m)"),
        "{imported}"
    );
    let tables = &imported[imported.find("[[string]]").unwrap()..];
    let hand = tempfile::tempdir().unwrap();
    write_case(hand.path(), BY_HAND);
    let imp = tempfile::tempdir().unwrap();
    write_case(imp.path(), tables);
    let a = run_ok(hand.path(), &["solve", "case.toml", "--json"]);
    let b = run_ok(imp.path(), &["solve", "case.toml", "--json"]);
    for ((k, x), (_, y)) in numbers(&a.stdout).iter().zip(numbers(&b.stdout)) {
        assert!((x - y).abs() <= 1e-3 * x.abs().max(1e-9), "{k}: {x} against {y}");
    }
    // refusals: an existing case, an input as the output, a file of another object
    let r = run_in(d.path(), &["import", "bha.xml", "--out", "case.toml"]);
    assert_error_names(&r, &["option `--out`: case.toml exists", "--force"]);
    let r = run_in(d.path(), &["import", "bha.xml", "--out", "bha.xml", "--force"]);
    assert_error_names(&r, &["is an input of this run"]);
    std::fs::write(
        d.path().join("wells.xml"),
        "<wells xmlns=\"http://www.witsml.org/schemas/1series\"/>",
    )
    .unwrap();
    let r = run_in(d.path(), &["import", "wells.xml", "--out", "w.toml"]);
    assert_error_names(&r, &["wells.xml: root element `wells`"]);
    assert!(!d.path().join("w.toml").exists());
}

/// The tubular with a bent motor in place of the near-bit stabilizer (1.5 deg, 1 m above the
/// motor's bottom), and the same string by hand.
fn bent_motor() -> (String, String) {
    let xml = tubular("")
        .replace("near bit stabilizer</typeTubularComp>", "mud motor</typeTubularComp>")
        .replace(
            "<stabilizer uid=\"b2\"><lenBlade uom=\"m\">0.4</lenBlade><odBladeMx uom=\"in\">8.5</odBladeMx></stabilizer>",
            "<bend uid=\"b\"><angle uom=\"dega\">1.5</angle><distBendBot uom=\"m\">1</distBendBot></bend>",
        );
    let first_stab = "[[string]]\ntype = \"stabilizer\"\nod = \"6.5 in\"\nblade_od = \"8.5 in\"\nblade_length = \"0.4 m\"\nid = \"2.8125 in\"\nlength = \"1.6 m\"\n";
    assert!(BY_HAND.contains(first_stab));
    let motor = "[[string]]\ntype = \"motor\"\nod = \"6.5 in\"\nid = \"2.8125 in\"\nlength = \"1.6 m\"\nbend_angle = \"1.5 deg\"\nbend_to_bit = \"1.3 m\"\n";
    (xml, BY_HAND.replacen(first_stab, motor, 1))
}

#[test]
fn a_bent_motor_in_a_tubular_solves_like_the_case_written_by_hand() {
    let (xml, by_hand) = bent_motor();
    let hand = tempfile::tempdir().unwrap();
    write_case(hand.path(), &by_hand);
    let x = tempfile::tempdir().unwrap();
    write_case(x.path(), "");
    let case = std::fs::read_to_string(x.path().join("case.toml")).unwrap();
    std::fs::write(x.path().join("case.toml"), format!("string_from = \"bha.xml\"\n{case}")).unwrap();
    std::fs::write(x.path().join("bha.xml"), xml).unwrap();
    for dir in [hand.path(), x.path()] {
        let c = std::fs::read_to_string(dir.join("case.toml")).unwrap();
        std::fs::write(
            dir.join("case.toml"),
            c.replace("mode = \"drilling\"", "mode = \"sliding\""),
        )
        .unwrap();
    }
    let a = run_ok(hand.path(), &["solve", "case.toml", "--json", "--fidelity", "bha"]);
    let b = run_ok(x.path(), &["solve", "case.toml", "--json", "--fidelity", "bha"]);
    let j = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap();
    let (ja, jb) = (j(&a.stdout), j(&b.stdout));
    assert_eq!(
        jb["steering"]["bend_to_bit_m"].as_f64(),
        Some(1.3),
        "{}",
        jb["steering"]
    );
    for k in ["build_force_kN", "walk_force_kN"] {
        let (x, y) = (ja["bit"][k].as_f64().unwrap(), jb["bit"][k].as_f64().unwrap());
        assert!((x - y).abs() <= 1e-3 * x.abs().max(1e-6), "{k}: {x} against {y}");
    }
}
