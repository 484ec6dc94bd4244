//! The `flexrock` command: parses arguments, calls the library, maps errors to exit codes.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use flexrock::model::{Model, Overrides};
use flexrock::record_tools;

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
    /// Look at a ground-motion record before using it.
    Record {
        #[command(subcommand)]
        command: RecordCommand,
    },
}

#[derive(Subcommand)]
enum RecordCommand {
    /// Print what the reader understood: header, points, dt, duration, PGA and its time.
    Info {
        file: PathBuf,
        #[command(flatten)]
        options: RecordOptions,
    },
    /// Convert to CSV with columns t,acc_m_s2 (to standard output, or --out FILE).
    Csv {
        file: PathBuf,
        #[command(flatten)]
        options: RecordOptions,
        /// Write to this file (atomically) instead of standard output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(clap::Args)]
struct RecordOptions {
    /// peer-at2 or csv [default: from the extension].
    #[arg(long)]
    format: Option<String>,
    /// Units of the values: g, m/s2 or cm/s2 [default: g].
    #[arg(long, default_value = "g")]
    units: String,
    /// Sampling interval of a one-column CSV file, s.
    #[arg(long)]
    dt: Option<f64>,
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
        Command::Record { command } => match command {
            RecordCommand::Info { file, options } => {
                let record = record_tools::load(&file, options.format.as_deref(), options.dt)?;
                print!("{}", record_tools::info_text(&record, &options.units)?);
            }
            RecordCommand::Csv { file, options, out } => {
                let record = record_tools::load(&file, options.format.as_deref(), options.dt)?;
                let bytes = record_tools::csv_bytes(&record, &options.units)?;
                match out {
                    Some(path) => flexrock::output::write_file_atomically(&path, &bytes)?,
                    None => {
                        use std::io::Write;
                        let _ = std::io::stdout().write_all(&bytes);
                    }
                }
            }
        },
    }
    Ok(())
}

fn default_out_dir(model: &std::path::Path) -> PathBuf {
    let stem = model
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".to_string());
    PathBuf::from("out").join(stem)
}
