//! The `flexrock` command: parses arguments ([`cli`]), calls the library, maps errors to exit
//! codes.

mod cli;

use cli::{
    Cli, Command, FragilityArgs, PlotArgs, RecordCommand, RecordOptions, SetArgs, SweepArgs,
    SweepCommand,
};

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser as _;
use flexrock::commands::record as record_command;
use flexrock::figures::page::Format;
use flexrock_core::model::{FemOverrides, FemSetup, Model, Overrides};

/// A progress bar on standard error, drawn only on a terminal.
struct ProgressBar(indicatif::ProgressBar);

impl flexrock::commands::sweep::store::Progress for ProgressBar {
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
    use flexrock::commands::sweep::store;
    use flexrock_core::analysis::sweep::{axis, Request, Sweep};
    // Before anything is read or computed: the threads asked for, or refused.
    flexrock::commands::sweep::start_threads(args.store.threads)?;
    if let Some(SweepCommand::Merge { dirs, out }) = args.command {
        let report = store::merge(&dirs, &out)?;
        return Ok(Output {
            stdout: flexrock::commands::sweep::report_text(&report, None).into_bytes(),
            warnings: flexrock::commands::sweep::warnings(&report),
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
            chunk_size: args.store.chunk_size,
            rigid_form: match &args.rigid_form {
                Some(text) => Some(flexrock_core::bodies::rigid::RigidForm::parse(
                    "rigid_form",
                    text,
                )?),
                None => None,
            },
            rigid_overturning: match &args.rigid_overturning {
                Some(text) => Some(flexrock_core::bodies::rigid::RigidOverturning::parse(
                    "rigid_overturning",
                    text,
                )?),
                None => None,
            },
            rigid_restitution: args.rigid_restitution,
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
    let shard = match &args.store.shard {
        Some(text) => Some(store::Shard::parse(text)?),
        None => store::Shard::from_slurm(|name| std::env::var(name).ok())?,
    };
    let out = args.out.unwrap_or_else(|| default_out_dir(&path, "-sweep"));
    let bar = if args.store.quiet {
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
        force: args.store.force,
    };
    let report = store::run(&sweep, &target, &ProgressBar(bar.clone()))?;
    bar.finish_and_clear();
    Ok(Output {
        stdout: flexrock::commands::sweep::report_text(
            &report,
            Some(started.elapsed().as_secs_f64()),
        )
        .into_bytes(),
        warnings: flexrock::commands::sweep::warnings(&report),
    })
}

fn fragility(args: FragilityArgs) -> flexrock::Result<Output> {
    use flexrock::commands::fragility;
    use flexrock::commands::sweep::store;
    flexrock::commands::sweep::start_threads(args.store.threads)?;
    let measure = flexrock_core::analysis::fragility::Measure::parse("--im", &args.im)?;
    let (_, scale) = flexrock_core::analysis::sweep::axis::parse_interval(&format!(
        "excitation.scale={}",
        args.scale
    ))
    .map_err(|e| e.renamed("find_min excitation.scale", "--scale"))?;
    let shard = match &args.store.shard {
        Some(text) => Some(store::Shard::parse(text)?),
        None => store::Shard::from_slurm(|name| std::env::var(name).ok())?,
    };
    let options = fragility::Options {
        out: args
            .out
            .unwrap_or_else(|| default_out_dir(&args.model, "-fragility")),
        settings: args.set.settings_for(&args.model),
        model: args.model,
        records: args.records,
        measure,
        period: args.period,
        scale,
        scan: args.scan,
        tol: args.tol,
        bootstrap: args.bootstrap,
        seed: args.seed,
        chunk_size: args.store.chunk_size,
        shard,
        force: args.store.force,
        figures: args.figure.options(&[flexrock::figures::page::Format::Svg]),
    };
    options.figures.sizes.check()?;
    let bar = if args.store.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::with_draw_target(None, indicatif::ProgressDrawTarget::stderr())
    };
    let report = fragility::run(&options, &ProgressBar(bar.clone()))?;
    bar.finish_and_clear();
    let mut warnings = flexrock::commands::sweep::warnings(&report.sweep);
    if let Some(summary) = &report.summary {
        warnings.extend(summary.warnings.iter().cloned());
    }
    Ok(Output {
        stdout: fragility::report_text(&report).into_bytes(),
        warnings,
    })
}

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
        Command::Fragility(args) => fragility(args),
        Command::Criteria {
            model,
            out,
            figure,
            slenderness,
            record,
            check_record,
        } => {
            let figure_options = figure.options(&flexrock::commands::criteria::FIGURE_FORMATS);
            figure_options.sizes.check()?;
            flexrock::writers::check_creatable(&out)?;
            let report = flexrock::commands::criteria::run(
                &model,
                &slenderness,
                &record,
                &check_record,
                &out,
                &figure_options,
            )?;
            Ok(Output {
                stdout: flexrock::commands::criteria::report_text(&report).into_bytes(),
                warnings: Vec::new(),
            })
        }
        Command::Props { model, json, set } => props(&model, json, set),
        Command::Rigid {
            model: path,
            out,
            form,
            overturning,
            restitution,
            duration,
            find_min,
            scan,
            tol,
            set,
        } => {
            use flexrock_core::bodies::rigid::{check_restitution, RigidForm, RigidOverturning};
            if find_min.is_none() {
                for (flag, given) in [("--scan", scan.is_some()), ("--tol", tol.is_some())] {
                    if given {
                        return Err(flexrock_core::Error::invalid(
                            flag,
                            "(given)",
                            "sets the search of --find-min, which was not asked for",
                        )
                        .into());
                    }
                }
            }
            let search = find_min
                .as_deref()
                .map(flexrock_core::analysis::sweep::axis::parse_interval)
                .transpose()?;
            let options = flexrock_core::analysis::sweep::HousnerOptions {
                form: form
                    .as_deref()
                    .map(|f| RigidForm::parse("--form", f))
                    .transpose()?
                    .unwrap_or_default(),
                overturning: overturning
                    .as_deref()
                    .map(|o| RigidOverturning::parse("--overturning", o))
                    .transpose()?
                    .unwrap_or_default(),
                restitution: match restitution {
                    Some(e) => {
                        check_restitution("--restitution", e)?;
                        Some(e)
                    }
                    None => None,
                },
            };
            let overrides = Overrides {
                duration,
                settings: set.settings_for(&path),
                ..Overrides::default()
            };
            let model = load(&path, &overrides)?;
            let out = out.unwrap_or_else(|| default_out_dir(&path, "-rigid"));
            flexrock::writers::check_creatable(&out)?;
            let search = match search {
                None => None,
                Some((key, interval)) => {
                    let model_at = |value: f64| {
                        let mut at = overrides.clone();
                        at.settings
                            .push(flexrock_core::model::Setting::number(&key, value));
                        Model::load(&path, &at)
                    };
                    Some(flexrock_core::analysis::rigid_search::search_rigid(
                        &key,
                        interval,
                        (scan, tol),
                        options,
                        model_at,
                    )?)
                }
            };
            let report = flexrock::commands::rigid::run(&model, &options, search, &out)?;
            Ok(Output::text(flexrock::commands::rigid::report_text(
                &report,
            )))
        }
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
            check,
            plot,
            shapes_at,
            figure,
            timings,
        } => {
            if !plot && shapes_at.is_none() {
                refuse_figure_flags(&figure, "they set the figures of --plot (and --shapes-at)")?;
            }
            let overrides = Overrides {
                method,
                rtol,
                atol,
                duration,
                dt,
                newmark_variant: variant,
                settings: set.settings_for(&path),
            };
            run(
                &path,
                out,
                &overrides,
                (check, plot),
                shapes_at.as_deref(),
                &figure,
                timings.wall_times(),
            )
        }
        Command::Plot(args) => plot(args),
        Command::Events {
            dir,
            csv,
            json,
            episodes,
        } => events(&dir, csv, json, episodes),
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
            figure,
            dt,
            variant,
            reference_rtol,
            duration,
            set,
            timings,
        } => {
            let model = load_with_duration(&path, duration, set)?;
            let options = flexrock::commands::compare::CompareOptions {
                reference_rtol,
                dt,
                variant,
                wall_times: timings.wall_times(),
                figures: figure.checked(&[Format::Svg])?,
            };
            let out = out.unwrap_or_else(|| default_out_dir(&path, "-compare"));
            flexrock::writers::check_creatable(&out)?;
            compare(&model, &options, out)
        }
        Command::Converge {
            model: path,
            out,
            figure,
            dt,
            rtol,
            reference_rtol,
            duration,
            set,
            timings,
        } => {
            let model = load_with_duration(&path, duration, set)?;
            let options = flexrock::commands::converge::ConvergeOptions {
                dts: dt,
                rtols: rtol,
                reference_rtol,
                wall_times: timings.wall_times(),
                figures: figure.checked(&[Format::Svg])?,
            };
            let out = out.unwrap_or_else(|| default_out_dir(&path, "-converge"));
            flexrock::writers::check_creatable(&out)?;
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
            let inputs = flexrock::commands::report::ReportInputs {
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
            figure,
            set,
            timings,
        } => {
            if modes {
                refuse_figure_flags(&figure, "--modes prints the periods and draws no figure")?;
            }
            let figures = figure.checked(&[Format::Svg])?;
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
                flexrock::writers::check_creatable(&out)?;
                fem_pushover(&model, &setup, out, timings.wall_times(), &figures)
            } else {
                let out = out.unwrap_or_else(|| default_out_dir(&path, "-fem"));
                flexrock::writers::check_creatable(&out)?;
                fem(&model, &setup, out, compare, timings.wall_times(), &figures)
            }
        }
    }
}

/// Refuses a figure flag given to a command that draws nothing with it (`why` says so).
fn refuse_figure_flags(figure: &cli::FigureArgs, why: &str) -> flexrock::Result<()> {
    match figure.given() {
        Some((flag, value)) => Err(flexrock_core::Error::invalid(flag, value, why).into()),
        None => Ok(()),
    }
}

/// `flexrock props`: the body and its derived constants, as a table or as JSON.
fn props(path: &std::path::Path, json: bool, set: SetArgs) -> flexrock::Result<Output> {
    let model = load(path, &set.overrides(path))?;
    Ok(if json {
        Output {
            stdout: flexrock::writers::json_bytes(&flexrock::commands::run::properties(&model)),
            warnings: Vec::new(),
        }
    } else {
        Output::text(flexrock::commands::run::properties_table(&model))
    })
}

/// `flexrock run`: solves the model and writes its run directory (`out`, else out/<model stem>).
fn run(
    path: &std::path::Path,
    out: Option<PathBuf>,
    overrides: &Overrides,
    (check, plot): (bool, bool),
    shapes_at: Option<&str>,
    figure: &cli::FigureArgs,
    wall_times: flexrock::writers::WallTimes,
) -> flexrock::Result<Output> {
    if is_row_model(path) {
        let figures = figure.checked(&flexrock::figures::row::FORMATS)?;
        return run_row(path, out, overrides, (check, plot), shapes_at, &figures);
    }
    if let Some(times) = shapes_at {
        return Err(flexrock_core::Error::invalid(
            "--shapes-at",
            times.to_string(),
            "applies only to a row model (a file with a [row] table): it sets the times of the \
             strip of the row's shapes, row_shapes.svg",
        )
        .into());
    }
    let model = load(path, overrides)?;
    let out = out.unwrap_or_else(|| default_out_dir(path, ""));
    flexrock::writers::check_creatable(&out)?;
    let options = flexrock::commands::run::RunOptions {
        check,
        plots: plot,
        figures: figure.checked(&[flexrock::figures::page::Format::Svg])?,
        wall_times,
    };
    let report = flexrock::commands::run::run_to_dir_checked(&model, &out, &options)?;
    Ok(Output {
        stdout: flexrock::commands::run::run_report_text(&model, &report).into_bytes(),
        warnings: report.warnings.clone(),
    })
}

/// True when `path` reads as a model file with a `[row]` table (a file that does not read is
/// left to the single body's loader, whose messages say why).
fn is_row_model(path: &std::path::Path) -> bool {
    flexrock_core::model::read_model_table(path)
        .is_ok_and(|(_, table)| flexrock_core::model::is_row_table(&table))
}

/// `flexrock run` on a row model: only `--duration`, `--out`, `--plot` and `--shapes-at` apply.
fn run_row(
    path: &std::path::Path,
    out: Option<PathBuf>,
    overrides: &Overrides,
    (check, plot): (bool, bool),
    shapes_at: Option<&str>,
    figures: &flexrock::figures::page::FigureOptions,
) -> flexrock::Result<Output> {
    let refuse = |flag: &str, value: String| -> flexrock::Result<Output> {
        Err(flexrock_core::Error::invalid(
            flag,
            value,
            "not an option of a row model: a row's method is its model file's (the exact \
             method under the impact law, tsit45 with its rtol and atol under the compliant \
             law), and --check, --set and the solver flags do not apply to it",
        )
        .into())
    };
    let given: [(&str, Option<String>); 6] = [
        ("--method", overrides.method.clone()),
        ("--rtol", overrides.rtol.map(|x| x.to_string())),
        ("--atol", overrides.atol.map(|x| x.to_string())),
        ("--dt", overrides.dt.map(|x| x.to_string())),
        ("--variant", overrides.newmark_variant.clone()),
        ("--check", check.then(|| "true".to_string())),
    ];
    for (flag, value) in given {
        if let Some(value) = value {
            return refuse(flag, value);
        }
    }
    if let Some(setting) = overrides.settings.first() {
        return refuse(&format!("--set {}", setting.key), setting.value_text());
    }
    let model = flexrock_core::model::RowModel::load(path, overrides.duration)
        .map_err(|e| e.renamed("simulation.duration", "--duration"))?;
    let out = out.unwrap_or_else(|| default_out_dir(path, ""));
    flexrock::writers::check_creatable(&out)?;
    // The strip's times are checked against the row's duration before anything is written.
    let shapes_at = shapes_at
        .map(|text| flexrock::figures::row::parse_shape_times(text, model.duration))
        .transpose()?;
    let report =
        flexrock::commands::row::run_row_to_dir(&model, &out, plot, shapes_at.as_deref(), figures)?;
    Ok(Output {
        stdout: flexrock::commands::row::row_report_text(&model, &report).into_bytes(),
        warnings: flexrock_core::simulate::row_warnings(&model, &report.solution),
    })
}

/// `flexrock plot`: the figures of a run or sweep directory.
fn plot(args: PlotArgs) -> flexrock::Result<Output> {
    let figure = args.figure.options(&[Format::Svg]);
    let written =
        if args.dir.join("sweep.json").is_file() && !args.dir.join("summary.json").exists() {
            for (flag, given) in [("--from", args.from), ("--to", args.to)] {
                if let Some(t) = given {
                    return Err(flexrock_core::Error::InvalidParameter {
                        key: flag.to_string(),
                        value: t.to_string(),
                        rule: format!(
                            "applies to a run's figures only; {} is a sweep's directory",
                            args.dir.display()
                        ),
                    }
                    .into());
                }
            }
            flexrock::commands::sweep::store::plot_dir(&args.dir, &figure)?
        } else {
            let options = flexrock::figures::run::PlotOptions {
                formats: figure.formats,
                sizes: figure.sizes,
                from: args.from,
                to: args.to,
            };
            flexrock::figures::run::plot_dir_with(&args.dir, &options)?
        };
    Ok(Output::text(
        written
            .iter()
            .map(|f| format!("wrote {}\n", f.display()))
            .collect::<String>(),
    ))
}

/// `flexrock events`: the events of a run directory as a table, CSV or JSON, or its episodes as
/// CSV or JSON.
fn events(
    dir: &std::path::Path,
    csv: bool,
    json: bool,
    episodes: bool,
) -> flexrock::Result<Output> {
    use flexrock::writers::run_dir::{read_table_csv, table_json, RunTable};
    let table = if episodes {
        RunTable::Episodes
    } else {
        RunTable::Events
    };
    if csv || json || episodes {
        let bytes = read_table_csv(dir, table)?;
        if !json {
            return Ok(Output {
                stdout: bytes,
                warnings: Vec::new(),
            });
        }
        let value = table_json(&bytes, &dir.join(table.file()), table)?;
        return Ok(Output {
            stdout: flexrock::writers::json_bytes(&value),
            warnings: Vec::new(),
        });
    }
    let events = flexrock::writers::run_dir::read_events(dir)?;
    Ok(Output::text(flexrock::writers::run_dir::events_table(
        &events,
        &dir.join(flexrock::writers::run_dir::EVENTS_FILE),
    )))
}

/// `flexrock record info` and `flexrock record csv`.
fn record(command: RecordCommand) -> flexrock::Result<Output> {
    // Standard output, or the file `out` written atomically.
    let emit = |bytes: Vec<u8>, out: Option<PathBuf>| -> flexrock::Result<Output> {
        match out {
            Some(path) => {
                flexrock::writers::write_file_atomically(&path, &bytes)?;
                Ok(Output::default())
            }
            None => Ok(Output {
                stdout: bytes,
                warnings: Vec::new(),
            }),
        }
    };
    match command {
        RecordCommand::Info {
            file,
            options,
            oscillator,
        } => {
            record_command::check_periods(&oscillator.period, oscillator.damping)?;
            let record = load_record(&file, &options)?;
            Ok(Output::text(record_command::info_text(
                &record,
                &oscillator.period,
                oscillator.damping,
            )?))
        }
        RecordCommand::Csv { file, options, out } => {
            let record = load_record(&file, &options)?;
            emit(record_command::csv_bytes(&record), out)
        }
        RecordCommand::Intensity {
            files,
            options,
            period,
            damping,
            out,
        } => {
            let periods: Vec<f64> = period.into_iter().collect();
            record_command::check_periods(&periods, damping)?;
            let mut records = Vec::new();
            for (path, scale) in record_command::expand_inputs(&files)? {
                records.push((load_record(&path, &options)?, scale));
            }
            emit(
                record_command::intensity_csv(&records, period, damping)?,
                out,
            )
        }
        RecordCommand::Spectrum {
            file,
            options,
            periods,
            damping,
            out,
        } => {
            let periods = if periods.is_empty() {
                flexrock_core::bodies::oscillator::default_periods()
            } else {
                periods
            };
            record_command::check_periods(&periods, damping)?;
            let record = load_record(&file, &options)?;
            emit(
                record_command::spectrum_csv(&record, &periods, damping)?,
                out,
            )
        }
    }
}

/// `flexrock compare`: Newmark against the adaptive reference, files into `out`.
fn compare(
    model: &Model,
    options: &flexrock::commands::compare::CompareOptions,
    out: PathBuf,
) -> flexrock::Result<Output> {
    let report = flexrock::commands::compare::run_compare(model, options, &out)?;
    Ok(Output::text(flexrock::commands::compare::compare_text(
        model, &report,
    )))
}

/// `flexrock converge`: the convergence study, files into `out`.
fn converge(
    model: &Model,
    options: &flexrock::commands::converge::ConvergeOptions,
    out: PathBuf,
) -> flexrock::Result<Output> {
    let report = flexrock::commands::converge::run_converge(model, options, &out)?;
    Ok(Output::text(flexrock::commands::converge::converge_text(
        &report,
    )))
}

/// `flexrock report`: the validation report from the output directories in `inputs`.
fn report(
    inputs: &flexrock::commands::report::ReportInputs,
    out: &std::path::Path,
) -> flexrock::Result<Output> {
    let written = flexrock::commands::report::write_report(inputs, out)?;
    Ok(Output::text(format!("wrote {}\n", written.display())))
}

/// `flexrock fem --modes`: the fixed-base periods of the mesh.
fn fem_modes(model: &Model, setup: &FemSetup) -> flexrock::Result<Output> {
    use flexrock::commands::fem;
    Ok(Output::text(fem::modes_text(&fem::modes(model, setup)?)))
}

/// `flexrock fem --pushover`: the pushover curves, files into `out`.
fn fem_pushover(
    model: &Model,
    setup: &FemSetup,
    out: PathBuf,
    wall_times: flexrock::writers::WallTimes,
    figures: &flexrock::figures::page::FigureOptions,
) -> flexrock::Result<Output> {
    let report = flexrock::commands::pushover::run(model, setup, &out, wall_times, figures)?;
    Ok(Output::text(flexrock::commands::pushover::report_text(
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
    wall_times: flexrock::writers::WallTimes,
    figures: &flexrock::figures::page::FigureOptions,
) -> flexrock::Result<Output> {
    use flexrock::commands::fem;
    let report = if compare {
        fem::compare(model, setup, &out, wall_times, figures)?
    } else {
        fem::fem(model, setup, &out, wall_times, figures)?
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
) -> flexrock::Result<record_command::LoadedRecord> {
    record_command::load(
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
