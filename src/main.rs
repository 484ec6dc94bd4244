//! The `flexrock` command: parses arguments, calls the library, maps errors to exit codes.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use flexrock::model::{FemOverrides, Model, Overrides};

#[derive(Parser)]
#[command(
    name = "flexrock",
    version,
    about = "Slender elastic body rocking on a rigid floor (Ichinose 1986): event-driven reference solutions"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the body's derived constants.
    Props {
        /// Model file (TOML).
        model: PathBuf,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Simulate a model and write history.csv, events.csv and summary.json.
    Run {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Relative tolerance (overrides solver.rtol).
        #[arg(long)]
        rtol: Option<f64>,
        /// Absolute tolerance (overrides solver.atol).
        #[arg(long)]
        atol: Option<f64>,
        /// Integration method: bdf, esdirk34 or tr-bdf2 (overrides solver.method).
        #[arg(long)]
        method: Option<String>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long)]
        duration: Option<f64>,
    },
    /// Plane-stress finite element analysis of the body (the paper's Section 3): writes
    /// fem_history.csv, fem_events.csv, fem_summary.json and SVG figures.
    Fem {
        /// Model file (TOML); its optional [fem] section holds the settings.
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-fem].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Elements across the width (overrides fem.nx).
        #[arg(long)]
        nx: Option<usize>,
        /// Elements up the height (overrides fem.ny).
        #[arg(long)]
        ny: Option<usize>,
        /// linear-acceleration, average-acceleration or wilson-theta (overrides fem.scheme).
        #[arg(long)]
        scheme: Option<String>,
        /// Time step, s (overrides fem.dt).
        #[arg(long)]
        dt: Option<f64>,
        /// Also solve the SDOF model and compare the two (table, compare.csv, figures).
        #[arg(long, conflicts_with = "modes")]
        compare: bool,
        /// Only print the fixed-base natural periods of the mesh against the SDOF period T.
        #[arg(long)]
        modes: bool,
    },
}

/// Exit code for bad input (model file, parameters).
const EXIT_INPUT: u8 = 2;
/// Exit code for a failure of the computation or of writing results.
const EXIT_FAILURE: u8 = 1;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(if e.is_input_error() {
                EXIT_INPUT
            } else {
                EXIT_FAILURE
            })
        }
    }
}

fn execute(command: Command) -> flexrock::Result<()> {
    match command {
        Command::Props { model, json } => {
            let model = Model::load(&model, &Overrides::default())?;
            if json {
                println!(
                    "{}",
                    String::from_utf8_lossy(&flexrock::output::json_bytes(
                        &flexrock::run::properties(&model)
                    ))
                    .trim_end()
                );
            } else {
                print!("{}", flexrock::run::properties_table(&model));
            }
        }
        Command::Run {
            model: path,
            out,
            rtol,
            atol,
            method,
            duration,
        } => {
            let overrides = Overrides {
                method,
                rtol,
                atol,
                duration,
            };
            let model = Model::load(&path, &overrides)?;
            let out = out.unwrap_or_else(|| default_out_dir(&path));
            let report = flexrock::run::run(&model, &out)?;
            print!("{}", flexrock::run::run_report_text(&model, &report));
        }
        Command::Fem {
            model: path,
            out,
            nx,
            ny,
            scheme,
            dt,
            compare,
            modes,
        } => {
            use flexrock::fem::run as fem;
            let model = Model::load(&path, &Overrides::default())?;
            let setup = model.fem_with(&FemOverrides { nx, ny, scheme, dt })?;
            if modes {
                print!("{}", fem::modes_text(&fem::modes(&model, &setup)?));
                return Ok(());
            }
            let out = out.unwrap_or_else(|| {
                default_out_dir(&path).with_file_name(format!("{}-fem", stem(&path)))
            });
            let report = if compare {
                fem::compare(&model, &setup, &out)?
            } else {
                fem::fem(&model, &setup, &out)?
            };
            for warning in &report.analysis.warnings {
                eprintln!("warning: {warning}");
            }
            print!("{}", fem::report_text(&report));
        }
    }
    Ok(())
}

fn default_out_dir(model: &std::path::Path) -> PathBuf {
    PathBuf::from("out").join(stem(model))
}

fn stem(model: &std::path::Path) -> String {
    model
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".to_string())
}
