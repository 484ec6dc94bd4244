//! The `flexrock` command: parses arguments, calls the library, maps errors to exit codes.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::LazyLock;

use clap::{Parser, Subcommand};
use flexrock::model::{FemOverrides, FemSetup, Model, Overrides, Setting};
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
        #[command(flatten)]
        set: SetArgs,
    },
    /// Simulate a model and write history.csv, events.csv, episodes.csv and summary.json.
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
        /// Integration method: bdf (implicit, the default), esdirk34, tr-bdf2 (implicit), tsit45
        /// (explicit) or newmark (fixed step) (overrides solver.method; switching between newmark
        /// and the adaptive methods sets aside the file's keys of the other).
        #[arg(long)]
        method: Option<String>,
        /// Newmark time step, s (overrides solver.dt; needs method newmark).
        #[arg(long)]
        dt: Option<f64>,
        /// Newmark variant at events: compensate or substep (overrides solver.newmark_variant).
        #[arg(long)]
        variant: Option<String>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        /// Also draw the figures of `flexrock plot` (plot_motion.svg, plot_force.svg,
        /// plot_energy.svg), written with the run's files as one set.
        #[arg(long)]
        plot: bool,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Draw the figures of a run directory (history.csv, events.csv, summary.json of
    /// `flexrock run`) into it: plot_motion (floor acceleration, q, s and r, dq/dt against t,
    /// with the events marked on every panel), plot_force (F(q), q against r, s against r) and
    /// plot_energy (energy balance and residual), as SVG, PNG or both.
    Plot(PlotArgs),
    /// Print the event log of a run directory (its events.csv) as a table, or with --csv or
    /// --json its rocking episodes (episodes.csv): one row per episode with its side, start,
    /// end, duration, peak |q| and rotation, floor acceleration at uplift and q' before and
    /// after each impact.
    Events {
        /// Output directory of `flexrock run`.
        dir: PathBuf,
        /// Print the rocking episodes as CSV (the run's episodes.csv).
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        /// Print the rocking episodes as JSON: an array of objects by column name.
        #[arg(long)]
        json: bool,
    },
    /// Parametric study: run the model at every point of a grid of model-file keys (or search
    /// the smallest overturning value at each), one row per point in sweep.csv, with sweep.json
    /// and a figure (SVG): a map over two numeric axes, a spectrum of a minimum search, or for
    /// records (excitation.path) against excitation.scale or excitation.amplitude an
    /// incremental dynamic analysis (ida.svg). Re-running the same command resumes an interrupted sweep.
    Sweep(SweepArgs),
    /// Print a shell completion script for flexrock (bash, zsh, fish, elvish or powershell),
    /// e.g. `flexrock completions bash > ~/.local/share/bash-completion/completions/flexrock`.
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print flexrock's manual page (roff), e.g. `flexrock man > flexrock.1; man ./flexrock.1`.
    Man,
    /// Look at a ground-motion record before using it.
    Record {
        #[command(subcommand)]
        command: RecordCommand,
    },
    /// Compare Newmark at the paper's dt with a tight adaptive reference; write compare.csv,
    /// compare_history.csv, compare.json, compare.svg and compare_relations.svg.
    Compare {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-compare].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Newmark time step, s [default: the file's solver.dt, else 0.02].
        #[arg(long)]
        dt: Option<f64>,
        /// Newmark variant at events: compensate or substep [default: the file's, else compensate].
        #[arg(long)]
        variant: Option<String>,
        /// Relative tolerance of the adaptive reference.
        #[arg(long, default_value = REFERENCE_RTOL_TEXT.as_str())]
        reference_rtol: f64,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Convergence study: Newmark at each dt and each adaptive method at each tolerance against
    /// a reference; write convergence.csv, convergence.json and two SVG figures.
    Converge {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-converge].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Newmark time steps, s, separated by commas.
        #[arg(long, value_delimiter = ',', default_value = DTS_TEXT.as_str())]
        dt: Vec<f64>,
        /// Relative tolerances of the adaptive methods, separated by commas.
        #[arg(long, value_delimiter = ',', default_value = RTOLS_TEXT.as_str())]
        rtol: Vec<f64>,
        /// Relative tolerance of the reference.
        #[arg(long, default_value = REFERENCE_RTOL_TEXT.as_str())]
        reference_rtol: f64,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Assemble the validation report (markdown) from the output directories of compare (both
    /// variants), converge and a run of the rigid-limit model.
    Report {
        #[arg(long)]
        compare_compensate: PathBuf,
        #[arg(long)]
        compare_substep: PathBuf,
        #[arg(long)]
        converge: PathBuf,
        #[arg(long)]
        rigid: PathBuf,
        /// Directory of the figures, as the report links them (relative to the report).
        #[arg(long, default_value = "figures")]
        figures: String,
        /// The regenerating command, quoted in the report.
        #[arg(long, default_value = "validation/regenerate.sh")]
        command: String,
        /// The report file to write.
        #[arg(long)]
        out: PathBuf,
    },
    /// Plane-stress finite element analysis of the body (the paper's Section 3): writes
    /// fem_history.csv, fem_events.csv, fem_summary.json and SVG figures.
    Fem {
        /// Model file (TOML); its optional [fem] section holds the settings.
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-fem, or out/<model file stem>-pushover
        /// with --pushover].
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
        #[arg(long, conflicts_with_all = ["modes", "pushover"])]
        compare: bool,
        /// Only print the fixed-base natural periods of the mesh against the SDOF period T.
        #[arg(long, conflicts_with = "pushover")]
        modes: bool,
        /// Instead of the dynamic run, push the body over statically (lateral loads m U(y), q up
        /// to B) on the flexible base and on a rigid base plate, against the SDOF model's F(q):
        /// writes pushover.csv, pushover.json and pushover.svg. Use a refined mesh (--nx 8 --ny 40).
        #[arg(long)]
        pushover: bool,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
}

/// `--timings-apart` of the commands that time their solves.
#[derive(clap::Args)]
struct TimingsArg {
    /// Write the wall-clock times to timings.json in the output directory instead of into the
    /// summaries (which then hold null, or an empty cell) and the printed text, so that every
    /// other file is the same from run to run.
    #[arg(long)]
    timings_apart: bool,
}

impl TimingsArg {
    fn wall_times(&self) -> flexrock::output::WallTimes {
        if self.timings_apart {
            flexrock::output::WallTimes::Apart
        } else {
            flexrock::output::WallTimes::Inline
        }
    }
}

/// The arguments of `flexrock plot`.
#[derive(clap::Args, Debug)]
struct PlotArgs {
    /// Output directory of `flexrock run`.
    dir: PathBuf,
    /// Image format: svg (plot_motion.svg, ...), png (plot_motion.png, ..., drawn with the
    /// embedded DejaVu Sans font, no system fonts needed) or both.
    #[arg(long, value_enum, default_value_t = PlotFormat::Svg)]
    format: PlotFormat,
    /// Width of every figure, pixels (200 to 6000) [default: 1150 for plot_motion and
    /// plot_energy, 1920 for plot_force].
    #[arg(long, value_name = "PX")]
    width: Option<u32>,
    /// Height of every figure, pixels (200 to 6000) [default: 1320 for plot_motion, 560 for
    /// plot_force, 760 for plot_energy].
    #[arg(long, value_name = "PX")]
    height: Option<u32>,
    /// Draw only from this time on, s (0 or more, finite, less than --to) [default: the start
    /// of the run]. The energy curves keep their values accumulated since t = 0.
    #[arg(long, value_name = "T0", allow_negative_numbers = true)]
    from: Option<f64>,
    /// Draw only up to this time, s (finite, more than --from) [default: the end of the run].
    #[arg(long, value_name = "T1", allow_negative_numbers = true)]
    to: Option<f64>,
}

/// The image formats of `flexrock plot`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum PlotFormat {
    /// SVG.
    Svg,
    /// PNG (8-bit RGB).
    Png,
    /// SVG and PNG.
    Both,
}

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct SweepArgs {
    #[command(subcommand)]
    command: Option<SweepCommand>,
    /// Model file (TOML): the base of every point.
    #[arg(required = true)]
    model: Option<PathBuf>,
    /// Output directory [default: out/<model file stem>-sweep].
    #[arg(long)]
    out: Option<PathBuf>,
    /// An axis, KEY=VALUES (repeatable): LO:HI:STEP, lin:LO:HI:N, log:LO:HI:N, a comma list, or
    /// for excitation.path a file pattern such as 'records/*.AT2'. The last axis varies fastest.
    #[arg(long, value_name = "KEY=VALUES")]
    vary: Vec<String>,
    /// Instead of one run per point, the smallest value of KEY in [LO, HI] that overturns the
    /// body: a scan of --scan values, then bisection of the first transition to --tol.
    #[arg(long, value_name = "KEY=LO:HI")]
    find_min: Option<String>,
    /// Values scanned by --find-min [default: 100].
    #[arg(long)]
    scan: Option<usize>,
    /// Width of the final bracket of --find-min, in KEY's units [default: (HI - LO)/1e4].
    #[arg(long)]
    tol: Option<f64>,
    /// A sweep file (TOML: vary, set, find_min, scan, tol); flags add to it.
    #[arg(long)]
    sweep_file: Option<PathBuf>,
    /// Compute only shard K of N (disjoint slices of whole chunks), into OUT/shard-K-of-N; set
    /// from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT in a Slurm job array.
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Points per chunk (what a kill can lose) [default: about 1024 simulations' worth].
    #[arg(long)]
    chunk_size: Option<usize>,
    /// Threads [default: every core].
    #[arg(long)]
    threads: Option<usize>,
    /// Replace the results of another sweep (or a damaged result of this one) in the output
    /// directory instead of refusing them; only the files a sweep writes are removed.
    #[arg(long)]
    force: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    #[command(flatten)]
    set: SetArgs,
}

#[derive(Subcommand)]
enum SweepCommand {
    /// Join the outputs of shards (directories of shards, or directories holding
    /// shard-K-of-N directories) into one, exactly as one process writes it; refuses gaps,
    /// overlaps and shards of different sweeps.
    Merge {
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
}

/// A progress bar on standard error, drawn only on a terminal.
struct ProgressBar(indicatif::ProgressBar);

impl flexrock::sweep::store::Progress for ProgressBar {
    fn start(&self, total: usize, done: usize) {
        self.0.set_length(total as u64);
        self.0.set_position(done as u64);
        self.0.reset_eta();
    }
    fn advance(&self, points: usize) {
        self.0.inc(points as u64);
    }
}

fn sweep(args: SweepArgs) -> flexrock::Result<Output> {
    use flexrock::sweep::{axis, store, Request, Sweep};
    if let Some(SweepCommand::Merge { dirs, out }) = args.command {
        let report = store::merge(&dirs, &out)?;
        return Ok(Output {
            stdout: flexrock::sweep::report_text(&report, None).into_bytes(),
            warnings: flexrock::sweep::warnings(&report),
        });
    }
    let Some(path) = args.model else {
        return Err(flexrock::Error::invalid(
            "MODEL",
            "(missing)",
            "name a model file",
        ));
    };
    let here = std::env::current_dir().unwrap_or_default();
    let sweep = (|| {
        let mut request = Request {
            settings: args.set.settings_for(&path),
            scan: args.scan,
            tol: args.tol,
            chunk_size: args.chunk_size,
            ..Request::default()
        };
        if let Some(file) = &args.sweep_file {
            request.add_file(file, &path, &here)?;
        }
        for text in &args.vary {
            request.vary(text, std::path::Path::new("."))?;
        }
        if let Some(text) = &args.find_min {
            request.find_min = Some(axis::parse_interval(text)?);
        }
        let given = Overrides {
            settings: request.settings.clone(),
            ..Overrides::default()
        };
        Sweep::new(&path, request, &here)
            .map_err(|e| flexrock::flags::named_by_flags(e, &given, &FemOverrides::default()))
    })()
    .map_err(flexrock::flags::sweep_named_by_flags)?;
    let shard = match &args.shard {
        Some(text) => Some(store::Shard::parse(text)?),
        None => store::Shard::from_slurm(|name| std::env::var(name).ok())?,
    };
    if let Some(threads) = args.threads {
        if threads == 0 {
            return Err(flexrock::Error::invalid(
                "--threads",
                0,
                "must be at least 1",
            ));
        }
        // Fails only if a pool exists already, which it cannot here.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global();
    }
    let out = args.out.unwrap_or_else(|| default_out_dir(&path, "-sweep"));
    let bar = if args.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::with_draw_target(None, indicatif::ProgressDrawTarget::stderr())
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} points, {per_sec}, {eta} left",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let started = std::time::Instant::now();
    let target = store::Target {
        out,
        shard,
        force: args.force,
    };
    let report = store::run(&sweep, &target, &ProgressBar(bar.clone()))?;
    bar.finish_and_clear();
    Ok(Output {
        stdout: flexrock::sweep::report_text(&report, Some(started.elapsed().as_secs_f64()))
            .into_bytes(),
        warnings: flexrock::sweep::warnings(&report),
    })
}

/// `--set KEY=VALUE`, any number of times: a model-file key set from the command line.
#[derive(clap::Args)]
struct SetArgs {
    /// Set a model-file key, e.g. --set excitation.amplitude=4.5 (repeatable; checked by the
    /// rules of the file; applied before the other flags).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = Setting::parse)]
    settings: Vec<Setting>,
}

impl SetArgs {
    /// The `--set` keys for the model file `model`: a record path typed here is relative to the
    /// current directory, and is written again relative to the model file, which reads it.
    fn settings_for(self, model: &std::path::Path) -> Vec<Setting> {
        let here = std::env::current_dir().unwrap_or_default();
        let model_dir = here.join(model.parent().unwrap_or(std::path::Path::new("")));
        self.settings
            .into_iter()
            .map(|s| s.rebased(&here, &model_dir))
            .collect()
    }

    fn overrides(self, model: &std::path::Path) -> Overrides {
        Overrides {
            settings: self.settings_for(model),
            ..Overrides::default()
        }
    }
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
    /// Units of the values: g, m/s2 or cm/s2 [default: g for AT2; for CSV the unit its header
    /// names (acc_m_s2, as `record csv` writes), else required].
    #[arg(long)]
    units: Option<String>,
    /// Sampling interval of a one-column CSV file, s.
    #[arg(long)]
    dt: Option<f64>,
}

/// The default lists of `converge` and the reference tolerance, as a user types them; the
/// numbers themselves live in the library.
static DTS_TEXT: LazyLock<String> = LazyLock::new(|| {
    flexrock::output::list(&flexrock::converge::DEFAULT_DTS, flexrock::output::shortest)
});
static RTOLS_TEXT: LazyLock<String> = LazyLock::new(|| {
    flexrock::output::list(
        &flexrock::converge::DEFAULT_RTOLS,
        flexrock::output::scientific,
    )
});
static REFERENCE_RTOL_TEXT: LazyLock<String> =
    LazyLock::new(|| flexrock::output::scientific(flexrock::compare::DEFAULT_REFERENCE_RTOL));

/// Exit code for bad input (model file, parameters): nothing was written.
const EXIT_INPUT: u8 = 2;
/// Exit code for a failure of the computation or of writing results (standard output included).
const EXIT_FAILURE: u8 = 1;

/// What a command has to say: its text for standard output and its warnings for standard error.
#[derive(Default)]
struct Output {
    stdout: Vec<u8>,
    warnings: Vec<String>,
}

impl Output {
    fn text(text: impl Into<String>) -> Self {
        Output {
            stdout: text.into().into_bytes(),
            warnings: Vec::new(),
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let output = match execute(cli.command) {
        Ok(output) => output,
        Err(e) => {
            write_stderr(&format!("error: {e}\n"));
            return ExitCode::from(if e.is_input_error() {
                EXIT_INPUT
            } else {
                EXIT_FAILURE
            });
        }
    };
    for warning in &output.warnings {
        write_stderr(&format!("warning: {warning}\n"));
    }
    match write_stdout(&output.stdout) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`flexrock ... | head`): what it did not read it did not want.
        // End quietly and successfully, as other Unix tools do.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            write_stderr(&format!("error: cannot write standard output: {e}\n"));
            ExitCode::from(EXIT_FAILURE)
        }
    }
}

/// The one place where command output reaches standard output: written whole and flushed, so
/// that every failure (a full disk, a closed pipe) is seen here.
fn write_stdout(bytes: &[u8]) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)?;
    out.flush()
}

/// Messages to standard error. A failure to write them cannot be reported anywhere, so it is
/// ignored (the exit code still tells).
fn write_stderr(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(text.as_bytes());
    let _ = err.flush();
}

/// Runs one subcommand: unpacks its arguments and calls the function that does it.
fn execute(command: Command) -> flexrock::Result<Output> {
    match command {
        Command::Sweep(args) => sweep(args),
        Command::Props { model, json, set } => props(&model, json, set),
        Command::Run {
            model: path,
            out,
            rtol,
            atol,
            method,
            dt,
            variant,
            duration,
            set,
            plot,
            timings,
        } => {
            let overrides = Overrides {
                method,
                rtol,
                atol,
                duration,
                dt,
                newmark_variant: variant,
                settings: set.settings_for(&path),
            };
            run(&path, out, &overrides, plot, timings.wall_times())
        }
        Command::Plot(args) => plot(args),
        Command::Events { dir, csv, json } => events(&dir, csv, json),
        Command::Completions { shell } => {
            let mut script = Vec::new();
            clap_complete::generate(
                shell,
                &mut <Cli as clap::CommandFactory>::command(),
                "flexrock",
                &mut script,
            );
            Ok(Output {
                stdout: script,
                warnings: Vec::new(),
            })
        }
        Command::Man => {
            let mut page = Vec::new();
            clap_mangen::Man::new(<Cli as clap::CommandFactory>::command())
                .render(&mut page)
                .map_err(|e| flexrock::Error::Write {
                    path: PathBuf::from("flexrock.1"),
                    source: e,
                })?;
            Ok(Output {
                stdout: page,
                warnings: Vec::new(),
            })
        }
        Command::Record { command } => record(command),
        Command::Compare {
            model: path,
            out,
            dt,
            variant,
            reference_rtol,
            duration,
            set,
            timings,
        } => {
            let model = load_with_duration(&path, duration, set)?;
            let options = flexrock::compare::CompareOptions {
                reference_rtol,
                dt,
                variant,
                wall_times: timings.wall_times(),
            };
            let out = out.unwrap_or_else(|| default_out_dir(&path, "-compare"));
            flexrock::output::check_creatable(&out)?;
            compare(&model, &options, out)
        }
        Command::Converge {
            model: path,
            out,
            dt,
            rtol,
            reference_rtol,
            duration,
            set,
            timings,
        } => {
            let model = load_with_duration(&path, duration, set)?;
            let options = flexrock::converge::ConvergeOptions {
                dts: dt,
                rtols: rtol,
                reference_rtol,
                wall_times: timings.wall_times(),
            };
            let out = out.unwrap_or_else(|| default_out_dir(&path, "-converge"));
            flexrock::output::check_creatable(&out)?;
            converge(&model, &options, out)
        }
        Command::Report {
            compare_compensate,
            compare_substep,
            converge,
            rigid,
            figures,
            command,
            out,
        } => {
            let inputs = flexrock::report::ReportInputs {
                compare_compensate,
                compare_substep,
                converge,
                rigid,
                figures_dir: figures,
                command,
            };
            report(&inputs, &out)
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
            pushover,
            set,
            timings,
        } => {
            let overrides = set.overrides(&path);
            let model = load(&path, &overrides)?;
            let fem_overrides = FemOverrides { nx, ny, scheme, dt };
            let setup = model
                .fem_with(&fem_overrides)
                .map_err(|e| flexrock::flags::named_by_flags(e, &overrides, &fem_overrides))?;
            if modes {
                fem_modes(&model, &setup)
            } else if pushover {
                let out = out.unwrap_or_else(|| default_out_dir(&path, "-pushover"));
                flexrock::output::check_creatable(&out)?;
                fem_pushover(&model, &setup, out, timings.wall_times())
            } else {
                let out = out.unwrap_or_else(|| default_out_dir(&path, "-fem"));
                flexrock::output::check_creatable(&out)?;
                fem(&model, &setup, out, compare, timings.wall_times())
            }
        }
    }
}

/// `flexrock props`: the body and its derived constants, as a table or as JSON.
fn props(path: &std::path::Path, json: bool, set: SetArgs) -> flexrock::Result<Output> {
    let model = load(path, &set.overrides(path))?;
    Ok(if json {
        Output {
            stdout: flexrock::output::json_bytes(&flexrock::run::properties(&model)),
            warnings: Vec::new(),
        }
    } else {
        Output::text(flexrock::run::properties_table(&model))
    })
}

/// `flexrock run`: solves the model and writes its run directory (`out`, else out/<model stem>).
fn run(
    path: &std::path::Path,
    out: Option<PathBuf>,
    overrides: &Overrides,
    plot: bool,
    wall_times: flexrock::output::WallTimes,
) -> flexrock::Result<Output> {
    let model = load(path, overrides)?;
    let out = out.unwrap_or_else(|| default_out_dir(path, ""));
    flexrock::output::check_creatable(&out)?;
    let report = flexrock::run::run_to_dir_with(&model, &out, plot, wall_times)?;
    Ok(Output {
        stdout: flexrock::run::run_report_text(&model, &report).into_bytes(),
        warnings: report.warnings.clone(),
    })
}

/// `flexrock plot`: the figures of a run directory.
fn plot(args: PlotArgs) -> flexrock::Result<Output> {
    use flexrock::plot::Format;
    let formats = match args.format {
        PlotFormat::Svg => vec![Format::Svg],
        PlotFormat::Png => vec![Format::Png],
        PlotFormat::Both => vec![Format::Svg, Format::Png],
    };
    let options = flexrock::run_plot::PlotOptions {
        formats,
        width: args.width,
        height: args.height,
        from: args.from,
        to: args.to,
    };
    let written = flexrock::run_plot::plot_dir_with(&args.dir, &options)?;
    Ok(Output::text(
        written
            .iter()
            .map(|f| format!("wrote {}\n", f.display()))
            .collect::<String>(),
    ))
}

/// `flexrock events`: the event table of a run directory, or its episodes as CSV or JSON.
fn events(dir: &std::path::Path, csv: bool, json: bool) -> flexrock::Result<Output> {
    use flexrock::run_dir::{episodes_json, read_episodes_csv, EPISODES_FILE};
    if csv || json {
        let bytes = read_episodes_csv(dir)?;
        if csv {
            return Ok(Output {
                stdout: bytes,
                warnings: Vec::new(),
            });
        }
        let value = episodes_json(&bytes, &dir.join(EPISODES_FILE))?;
        return Ok(Output {
            stdout: flexrock::output::json_bytes(&value),
            warnings: Vec::new(),
        });
    }
    let events = flexrock::run_dir::read_events(dir)?;
    Ok(Output::text(flexrock::run_dir::events_table(
        &events,
        &dir.join(flexrock::run_dir::EVENTS_FILE),
    )))
}

/// `flexrock record info` and `flexrock record csv`.
fn record(command: RecordCommand) -> flexrock::Result<Output> {
    Ok(match command {
        RecordCommand::Info { file, options } => {
            let record = load_record(&file, &options)?;
            Output::text(record_tools::info_text(&record))
        }
        RecordCommand::Csv { file, options, out } => {
            let record = load_record(&file, &options)?;
            let bytes = record_tools::csv_bytes(&record);
            match out {
                Some(path) => {
                    flexrock::output::write_file_atomically(&path, &bytes)?;
                    Output::default()
                }
                None => Output {
                    stdout: bytes,
                    warnings: Vec::new(),
                },
            }
        }
    })
}

/// `flexrock compare`: Newmark against the adaptive reference, files into `out`.
fn compare(
    model: &Model,
    options: &flexrock::compare::CompareOptions,
    out: PathBuf,
) -> flexrock::Result<Output> {
    let report = flexrock::compare::run_compare(model, options, &out)?;
    Ok(Output::text(flexrock::compare::compare_text(
        model, &report,
    )))
}

/// `flexrock converge`: the convergence study, files into `out`.
fn converge(
    model: &Model,
    options: &flexrock::converge::ConvergeOptions,
    out: PathBuf,
) -> flexrock::Result<Output> {
    let report = flexrock::converge::run_converge(model, options, &out)?;
    Ok(Output::text(flexrock::converge::converge_text(&report)))
}

/// `flexrock report`: the validation report from the output directories in `inputs`.
fn report(
    inputs: &flexrock::report::ReportInputs,
    out: &std::path::Path,
) -> flexrock::Result<Output> {
    let written = flexrock::report::write_report(inputs, out)?;
    Ok(Output::text(format!("wrote {}\n", written.display())))
}

/// `flexrock fem --modes`: the fixed-base periods of the mesh.
fn fem_modes(model: &Model, setup: &FemSetup) -> flexrock::Result<Output> {
    use flexrock::fem::run as fem;
    Ok(Output::text(fem::modes_text(&fem::modes(model, setup)?)))
}

/// `flexrock fem --pushover`: the pushover curves, files into `out`.
fn fem_pushover(
    model: &Model,
    setup: &FemSetup,
    out: PathBuf,
    wall_times: flexrock::output::WallTimes,
) -> flexrock::Result<Output> {
    let report = flexrock::fem::pushover_run::run(model, setup, &out, wall_times)?;
    Ok(Output::text(flexrock::fem::pushover_run::report_text(
        &report,
    )))
}

/// `flexrock fem` (with `--compare`, side by side with the one-mode model): the dynamic run,
/// files into `out`.
fn fem(
    model: &Model,
    setup: &FemSetup,
    out: PathBuf,
    compare: bool,
    wall_times: flexrock::output::WallTimes,
) -> flexrock::Result<Output> {
    use flexrock::fem::run as fem;
    let report = if compare {
        fem::compare(model, setup, &out, wall_times)?
    } else {
        fem::fem(model, setup, &out, wall_times)?
    };
    Ok(Output {
        stdout: fem::report_text(&report).into_bytes(),
        warnings: report.warnings.clone(),
    })
}

/// A record for the `record` commands, with its units resolved.
fn load_record(
    file: &std::path::Path,
    options: &RecordOptions,
) -> flexrock::Result<record_tools::LoadedRecord> {
    record_tools::load(
        file,
        options.format.as_deref(),
        options.dt,
        options.units.as_deref(),
    )
}

/// A model file with only the simulated time and `--set` keys overridden (compare, converge).
fn load_with_duration(
    path: &std::path::Path,
    duration: Option<f64>,
    set: SetArgs,
) -> flexrock::Result<Model> {
    let overrides = Overrides {
        duration,
        ..set.overrides(path)
    };
    load(path, &overrides)
}

/// Reads and validates the model file `path` with `overrides`; a message about a value a flag
/// gave names the flag.
fn load(path: &std::path::Path, overrides: &Overrides) -> flexrock::Result<Model> {
    Model::load(path, overrides)
        .map_err(|e| flexrock::flags::named_by_flags(e, overrides, &FemOverrides::default()))
}

fn default_out_dir(model: &std::path::Path, suffix: &str) -> PathBuf {
    let stem = model
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".to_string());
    PathBuf::from("out").join(format!("{stem}{suffix}"))
}
