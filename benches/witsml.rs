//! Reading a WITSML trajectory: a 1.2 MB file of 480 stations with raw sensor data
//! ([`drillpath::io::witsml::example::synthetic_trajectory`]), from its bytes to the validated
//! survey (UTF-8 check, XML parse, stations, units). Issue 22 asks under 50 ms.
//!
//! `cargo bench --bench witsml -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use drillpath::io::survey::{parse_survey, SurveyUnits};
use drillpath::io::witsml::example::synthetic_trajectory;

fn bench_witsml(c: &mut Criterion) {
    let text = synthetic_trajectory(480);
    println!("synthetic trajectory: {} bytes, 480 stations", text.len());
    let units = SurveyUnits::default();
    c.bench_function("witsml_trajectory_480_stations", |b| {
        b.iter(|| {
            let f = parse_survey(black_box(text.as_bytes()), Path::new("t.xml"), &units).unwrap();
            assert_eq!(f.survey.len(), 480);
        })
    });
}

criterion_group!(benches, bench_witsml);
criterion_main!(benches);
