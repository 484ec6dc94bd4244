fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/ichinose1986.toml");
    let overrides = flexrock::model::Overrides {
        rtol: Some(1e-8),
        ..Default::default()
    };
    let model = flexrock::model::Model::load(&path, &overrides).unwrap();
    let mut steps = 0;
    for _ in 0..2000 {
        steps += flexrock::run::simulate(&model).unwrap().stats.steps;
    }
    println!("{steps}");
}
