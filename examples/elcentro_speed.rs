use flexrock::automaton::Automaton;
use flexrock::excitation::RecordedMotion;
use flexrock::solver::adaptive::{solve, AdaptiveMethod, AdaptiveSettings};
use flexrock::solver::InitialState;
fn main() {
    let text = std::fs::read_to_string("/work/shared/records/elCentro.AT2").unwrap();
    let vals: Vec<f64> = text.lines().skip(4).flat_map(|l| l.split_whitespace().map(|x| x.parse::<f64>().unwrap() * 9.80665).collect::<Vec<_>>()).collect();
    let rec = RecordedMotion::new("el".into(), 0.02, vals);
    let model = flexrock::model::Model::load(std::path::Path::new("models/ichinose1986.toml"), &Default::default()).unwrap();
    let aut = Automaton::new(&model.constants);
    let method = match std::env::args().nth(1).as_deref() { Some("bdf") => AdaptiveMethod::Bdf, _ => AdaptiveMethod::Esdirk34 };
    let s = AdaptiveSettings { method, rtol: 1e-8, atol: 1e-10, output_dt: 0.005 };
    for _ in 0..100 { solve(&aut, &rec, InitialState { q: 0.0, qdot: 0.0 }, 32.0, &s).unwrap(); }
}
