use drillpath::case::Mode;
use drillpath::fem::model::Model;
use drillpath::fem::results::extract;
use drillpath::fem::solve::{solve, SolveControls};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::loads::chart::case_at_depth;
use drillpath::loads::{set_row_operation, ChartOperation};

#[test]
fn scratch() {
    for w in [
        "seed-daqing",
        "j-shape",
        "s-shape",
        "horizontal",
        "volve-f10",
        "forge-16a",
    ] {
        for acc in [
            drillpath::accuracy::Accuracy::Fast,
            drillpath::accuracy::Accuracy::Default,
        ] {
            let mut case = load_case(
                std::path::Path::new(&format!("wells/{w}/case.toml")),
                &CaseOverrides::default(),
            )
            .unwrap();
            acc.apply(&mut case.solver);
            let op = ChartOperation::from_case(&case);
            let bit = case.operation.bit_md_m;
            for mode in [Mode::TripIn, Mode::TripOut, Mode::Sliding] {
                let mut c = case_at_depth(&case, bit);
                set_row_operation(&mut c, bit, mode, &op);
                let model = Model::from_case(&c);
                let ctl = SolveControls::from_settings(&c.solver);
                let Ok(sol) = solve(&model, &ctl) else {
                    println!("{w} fail");
                    continue;
                };
                let res = extract(&model, &sol, c.mud.density_kg_m3);
                let fnr: f64 = (0..model.nodes())
                    .map(|i| model.friction[i] * res.nodes[i].contact_force_n * model.mesh.nodes[i].contact_od_m / 2.0)
                    .sum();
                println!(
                    "RES {w} {acc:?} {mode:?}: conv {} torque {:.4e} fNr {:.4e} ratio {:.2e}",
                    sol.converged,
                    res.surface_torque_nm,
                    fnr,
                    res.surface_torque_nm.abs() / fnr
                );
            }
        }
    }
}
