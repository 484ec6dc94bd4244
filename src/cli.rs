//! The command line's arguments: every command and flag, as clap types (the help texts are
//! their doc comments). `main.rs` runs what they ask for.

use std::path::PathBuf;
use std::sync::LazyLock;

use clap::{Parser, Subcommand};
use flexrock_core::model::{Overrides, Setting};

#[derive(Parser)]
#[command(
    name = "flexrock",
    version,
    about = "Slender elastic body rocking on a rigid floor (Ichinose 1986): event-driven reference solutions"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
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
        /// Model file (TOML): one body, or a row of columns (a [row] table and one [[column]]
        /// per column: each column's files, impacts.csv and summary.json; only --out,
        /// --duration, --plot and --shapes-at apply).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Relative tolerance (overrides solver.rtol).
        #[arg(long, allow_negative_numbers = true)]
        rtol: Option<f64>,
        /// Absolute tolerance (overrides solver.atol).
        #[arg(long, allow_negative_numbers = true)]
        atol: Option<f64>,
        /// Integration method: exact (closed form, the default), bdf (implicit, the default of a
        /// [solver] section that gives rtol or atol), esdirk34, tr-bdf2 (implicit), tsit45
        /// (explicit) or newmark (fixed step) (overrides solver.method; switching between exact,
        /// newmark and the adaptive methods sets aside the file's keys of the other).
        #[arg(long)]
        method: Option<String>,
        /// Newmark time step, s (overrides solver.dt; needs method newmark).
        #[arg(long, allow_negative_numbers = true)]
        dt: Option<f64>,
        /// Newmark variant at events: compensate or substep (overrides solver.newmark_variant).
        #[arg(long)]
        variant: Option<String>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long, allow_negative_numbers = true)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        /// Also solve the model exactly and write check.json: the run's error against the exact
        /// solution on every event, the peaks and the output grid (its certificate, for any
        /// method).
        #[arg(long)]
        check: bool,
        /// Also draw the figures of `flexrock plot` (plot_motion.svg, plot_force.svg,
        /// plot_energy.svg; a row's row_motion and row_shapes), written with the run's files as
        /// one set, in the formats and size of --format, --width and --height.
        #[arg(long)]
        plot: bool,
        /// A row only: the times (s, comma-separated, at most 8, within the duration) of the
        /// strip of the row's deformed shapes, row_shapes.svg and .png (drawn to true scale at
        /// the run's state at each time, which must be an instant of its history: a multiple of
        /// simulation.output_dt; drawn even without --plot). Without it, --plot draws the strip
        /// at instants chosen from the run (first uplift, first impact, largest lean, held
        /// contact, last impact, or the first instant after one).
        #[arg(long, value_name = "T1,T2,...", allow_hyphen_values = true)]
        shapes_at: Option<String>,
        #[command(flatten)]
        figure: FigureArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Draw the figures of a run directory (history.csv, events.csv, summary.json of
    /// `flexrock run`) into it: plot_motion (floor acceleration, q, s and r, q' against t,
    /// with the events marked), plot_force (F(q), q against r, s against r) and plot_energy
    /// (energy balance and residual); or those of a sweep directory (map, spectrum, ida or
    /// verdicts, from sweep.csv); as SVG, PDF or PNG, at a size on paper.
    Plot(PlotArgs),
    /// Print the event log of a run directory (its events.csv) as a table, as CSV (--csv) or
    /// as JSON (--json); with --episodes its rocking episodes (episodes.csv) instead, as CSV or
    /// JSON: one row per episode with its side, start, end, duration, peak |q| and rotation,
    /// floor acceleration at uplift and q' before and after each impact.
    Events {
        /// Output directory of `flexrock run`.
        dir: PathBuf,
        /// Print the table as CSV (the run's events.csv, or its episodes.csv).
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        /// Print the table as JSON: an array of objects by column name.
        #[arg(long)]
        json: bool,
        /// Print the rocking episodes (episodes.csv) instead of the events: as CSV, or as JSON
        /// with --json.
        #[arg(long)]
        episodes: bool,
    },
    /// Run Housner's rigid block of the body's height, width and gravity alone on the model's
    /// floor, its horizontal and vertical motions ([excitation.vertical]); write events.csv and
    /// summary.json.
    Rigid {
        /// Model file (TOML) of one body: its geometry, gravity and floor motion are used.
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-rigid].
        #[arg(long)]
        out: Option<PathBuf>,
        /// The block's equation: small-angle (q'' = k^2 (1 + a_v/g)(q - s B) - (3/2) a) or full
        /// (Housner's, theta'' = -p^2 [(1 + a_v/g) sin(s alpha - theta) + (a/g) cos(s alpha -
        /// theta)]) [default: small-angle].
        #[arg(long)]
        form: Option<String>,
        /// When it counts as overturned: reaches-limit (|theta| reaches the equation's unstable
        /// equilibrium) or cannot-return (it never comes back to the floor) [default:
        /// reaches-limit].
        #[arg(long)]
        overturning: Option<String>,
        /// Its own coefficient of restitution, strictly between 0 and 1 [default: Housner's,
        /// 1 - (3/2) sin^2 alpha].
        #[arg(long, allow_negative_numbers = true)]
        restitution: Option<f64>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long, allow_negative_numbers = true)]
        duration: Option<f64>,
        /// Also search the smallest value of a model-file key in [LO, HI] that overturns the
        /// block, e.g. excitation.amplitude=0.5:15 (a scan, then bisection of the first
        /// transition, as `flexrock sweep --find-min`); written to summary.json's find_min.
        #[arg(long, value_name = "KEY=LO:HI")]
        find_min: Option<String>,
        /// Values scanned by --find-min [default: 100].
        #[arg(long)]
        scan: Option<usize>,
        /// Width of --find-min's final bracket, in the key's units [default: 1e-4 of HI - LO].
        #[arg(long, allow_negative_numbers = true)]
        tol: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
    },
    /// Parametric study: run the model at every point of a grid of model-file keys (or search
    /// the smallest overturning value at each), one row per point in sweep.csv, with sweep.json
    /// and a figure (SVG): a map over two numeric axes, a spectrum of a minimum search, or for
    /// records (excitation.path) against excitation.scale an incremental dynamic analysis
    /// (ida.svg); a sweep over records adds each record's metadata and intensity measures to
    /// its rows. A row model (a [row] table) gives each column's
    /// outcome in the row and alone, with a verdict (saved, toppled, same) and, over two numeric
    /// axes, verdicts.svg and verdicts.png. Re-running the same command resumes an interrupted sweep.
    Sweep(SweepArgs),
    /// Fragility function of overturning over a suite of records, by incremental dynamic
    /// analysis: per record the smallest overturning excitation.scale (the sweep's minimum
    /// search, stored, resumed and sharded as a sweep in OUT/sweep), expressed in an intensity
    /// measure; a lognormal fit (censored records by their likelihood) with bootstrap intervals.
    /// Writes fragility.json, fragility.csv, fragility-pelicun.csv and figures (fragility,
    /// capacities).
    Fragility(FragilityArgs),
    /// Overturning criteria of elastic bodies of the model's geometry (and of other
    /// slendernesses B/H), E from near-rigid to beyond the paper's body, under sines, one-sine
    /// and one-cosine pulses and records, beside Housner's block: writes criteria.csv,
    /// continuity.csv, fit.json, criteria.json and figures (SVG and PNG).
    Criteria {
        /// Model file (TOML); only its [body] table is used.
        model: PathBuf,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        figure: FigureArgs,
        /// Another slenderness B/H of the body (its width over its height, the height and every
        /// other property kept), studied beside the model's own; may be repeated.
        #[arg(long, value_name = "B/H")]
        slenderness: Vec<f64>,
        /// A record (PEER AT2, in g) used for the fit; may be repeated.
        #[arg(long)]
        record: Vec<PathBuf>,
        /// A record only checked against the fit (not used for it); may be repeated.
        #[arg(long)]
        check_record: Vec<PathBuf>,
    },
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
    /// Compare Newmark at the paper's dt with the exact solution; write compare.csv,
    /// compare_history.csv, compare.json and the figures compare and compare_relations (SVG,
    /// PDF or PNG, at a size on paper).
    Compare {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-compare].
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        figure: FigureArgs,
        /// Newmark time step, s [default: the file's solver.dt, else 0.02].
        #[arg(long, allow_negative_numbers = true)]
        dt: Option<f64>,
        /// Newmark variant at events: compensate or substep [default: the file's, else compensate].
        #[arg(long)]
        variant: Option<String>,
        /// Relative tolerance of an adaptive reference (the file's adaptive method, BDF when it
        /// names another) [default: none, the reference is the exact solution].
        #[arg(long, allow_negative_numbers = true)]
        reference_rtol: Option<f64>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long, allow_negative_numbers = true)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Convergence study: Newmark at each dt and each adaptive method at each tolerance against
    /// the exact solution; write convergence.csv, convergence.json and two figures,
    /// convergence_dt and convergence_work (SVG, PDF or PNG, at a size on paper).
    Converge {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory [default: out/<model file stem>-converge].
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        figure: FigureArgs,
        /// Newmark time steps, s, separated by commas.
        #[arg(long, value_delimiter = ',', default_value = DTS_TEXT.as_str())]
        dt: Vec<f64>,
        /// Relative tolerances of the adaptive methods, separated by commas.
        #[arg(long, value_delimiter = ',', default_value = RTOLS_TEXT.as_str())]
        rtol: Vec<f64>,
        /// Relative tolerance of an adaptive reference (the file's adaptive method, BDF when it
        /// names another) [default: none, the reference is the exact solution].
        #[arg(long, allow_negative_numbers = true)]
        reference_rtol: Option<f64>,
        /// Simulated time, s (overrides simulation.duration).
        #[arg(long, allow_negative_numbers = true)]
        duration: Option<f64>,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
    /// Assemble the validation report (markdown) from the output directories of compare (both
    /// variants), converge and a run of the rigid-limit model.
    Report {
        /// Output directory of `flexrock compare` with the compensate variant.
        #[arg(long)]
        compare_compensate: PathBuf,
        /// Output directory of `flexrock compare` with the substep variant.
        #[arg(long)]
        compare_substep: PathBuf,
        /// Output directory of `flexrock converge`.
        #[arg(long)]
        converge: PathBuf,
        /// Output directory of `flexrock run` on the rigid-limit model.
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
    /// fem_history.csv, fem_events.csv, fem_summary.json and figures (SVG, PDF or PNG, at a
    /// size on paper).
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
        #[arg(long, allow_negative_numbers = true)]
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
        figure: FigureArgs,
        #[command(flatten)]
        set: SetArgs,
        #[command(flatten)]
        timings: TimingsArg,
    },
}

/// `--timings-apart` of the commands that time their solves.
#[derive(clap::Args)]
pub(crate) struct TimingsArg {
    /// Write the wall-clock times to timings.json in the output directory instead of into the
    /// summaries (which then hold null, or an empty cell) and the printed text, so that every
    /// other file is the same from run to run.
    #[arg(long)]
    pub(crate) timings_apart: bool,
}

impl TimingsArg {
    pub(crate) fn wall_times(&self) -> flexrock::writers::WallTimes {
        if self.timings_apart {
            flexrock::writers::WallTimes::Apart
        } else {
            flexrock::writers::WallTimes::Inline
        }
    }
}

/// The arguments of `flexrock plot`.
#[derive(clap::Args, Debug)]
pub(crate) struct PlotArgs {
    /// Output directory of `flexrock run` (summary.json, history.csv, events.csv) or of
    /// `flexrock sweep` (sweep.json, sweep.csv).
    pub(crate) dir: PathBuf,
    #[command(flatten)]
    pub(crate) figure: FigureArgs,
    /// Draw only from this time on, s (0 or more, finite, less than --to) [default: the start
    /// of the run]. The energy curves keep their values accumulated since t = 0. A run's only.
    #[arg(long, value_name = "T0", allow_negative_numbers = true)]
    pub(crate) from: Option<f64>,
    /// Draw only up to this time, s (finite, more than --from) [default: the end of the run].
    #[arg(long, value_name = "T1", allow_negative_numbers = true)]
    pub(crate) to: Option<f64>,
}

/// The formats and size of a command's figures.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct FigureArgs {
    /// Figure formats, comma-separated: svg, pdf (vector, its font embedded), png (at --dpi);
    /// `both` is svg,png [default: the command's own, svg for most].
    #[arg(long, value_enum, value_delimiter = ',', value_name = "FORMATS")]
    pub(crate) format: Vec<PlotFormat>,
    /// Width of every figure on paper: 85mm (one journal column), 180mm (two), 3.5in, 8.5cm,
    /// 250pt, or a bare number in pixels of 1/96 in as SVG counts them (40 mm to 500 mm)
    /// [default: 180mm]. Text keeps its size in points (7-9 pt); the layout adapts.
    #[arg(long, value_name = "LENGTH", value_parser = parse_length)]
    pub(crate) width: Option<flexrock::figures::page::Length>,
    /// Height of every figure on paper, as --width (20 mm to 500 mm) [default: as the
    /// figure's panels need at its width].
    #[arg(long, value_name = "LENGTH", value_parser = parse_length)]
    pub(crate) height: Option<flexrock::figures::page::Length>,
    /// Resolution of PNG figures, dots per inch (50 to 1200) [default: 300].
    #[arg(long, value_name = "DPI")]
    pub(crate) dpi: Option<f64>,
}

impl FigureArgs {
    /// The first of these flags given, and its value as typed, for a command that draws
    /// nothing with them.
    pub(crate) fn given(&self) -> Option<(&'static str, String)> {
        if let Some(f) = self.format.first() {
            return Some(("--format", format!("{f:?}").to_lowercase()));
        }
        if let Some(w) = self.width {
            return Some(("--width", w.to_string()));
        }
        if let Some(h) = self.height {
            return Some(("--height", h.to_string()));
        }
        self.dpi.map(|d| ("--dpi", d.to_string()))
    }

    /// As [`FigureArgs::options`], the sizes checked (the error names the flag, its value and
    /// the rule) before anything is computed.
    pub(crate) fn checked(
        &self,
        default: &[flexrock::figures::page::Format],
    ) -> flexrock::Result<flexrock::figures::page::FigureOptions> {
        let options = self.options(default);
        options.sizes.check()?;
        Ok(options)
    }

    /// The options these flags give, `default` the formats when none is asked.
    pub(crate) fn options(
        &self,
        default: &[flexrock::figures::page::Format],
    ) -> flexrock::figures::page::FigureOptions {
        use flexrock::figures::page::Format;
        let mut formats = Vec::new();
        for f in &self.format {
            let these: &[Format] = match f {
                PlotFormat::Svg => &[Format::Svg],
                PlotFormat::Pdf => &[Format::Pdf],
                PlotFormat::Png => &[Format::Png],
                PlotFormat::Both => &[Format::Svg, Format::Png],
            };
            for &format in these {
                if !formats.contains(&format) {
                    formats.push(format);
                }
            }
        }
        if formats.is_empty() {
            formats = default.to_vec();
        }
        flexrock::figures::page::FigureOptions {
            formats,
            sizes: flexrock::figures::page::Sizes {
                width: self.width,
                height: self.height,
                dpi: self.dpi,
            },
        }
    }
}

fn parse_length(text: &str) -> Result<flexrock::figures::page::Length, String> {
    flexrock::figures::page::Length::parse(text)
}

/// The image formats of a figure.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PlotFormat {
    /// SVG, sized in millimetres.
    Svg,
    /// A vector PDF with its font embedded.
    Pdf,
    /// PNG (8-bit RGBA) at --dpi.
    Png,
    /// SVG and PNG.
    Both,
}

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub(crate) struct SweepArgs {
    #[command(subcommand)]
    pub(crate) command: Option<SweepCommand>,
    /// Model file (TOML): the base of every point.
    #[arg(required = true)]
    pub(crate) model: Option<PathBuf>,
    /// Output directory [default: out/<model file stem>-sweep].
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
    /// An axis, KEY=VALUES (repeatable): LO:HI:STEP, lin:LO:HI:N, log:LO:HI:N, a comma list, or
    /// for excitation.path a file pattern such as 'records/*.AT2'. The last axis varies fastest.
    /// In a row model: row.gaps (every gap), row.gaps.I (the gap right of column I), column.I.KEY
    /// (column I's key, from 0), column.KEY (every column's).
    #[arg(long, value_name = "KEY=VALUES")]
    pub(crate) vary: Vec<String>,
    /// Instead of one run per point, the smallest value of KEY in [LO, HI] that overturns the
    /// body: a scan of --scan values, then bisection of the first transition to --tol. Not for a
    /// row model.
    #[arg(long, value_name = "KEY=LO:HI")]
    pub(crate) find_min: Option<String>,
    /// Values scanned by --find-min [default: 100].
    #[arg(long)]
    pub(crate) scan: Option<usize>,
    /// Width of the final bracket of --find-min, in KEY's units [default: (HI - LO)/1e4].
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) tol: Option<f64>,
    /// The equation of Housner's rigid block searched beside the body by --find-min: the
    /// small-angle (linearised) one, or the full one [default: small-angle]. A full-form sweep's
    /// sweep.csv has a rigid_form column.
    #[arg(long, value_name = "FORM", value_parser = ["small-angle", "full"])]
    pub(crate) rigid_form: Option<String>,
    /// When Housner's rigid block searched by --find-min counts as overturned: when its tilt
    /// reaches its limit, or only once it cannot come back, the rule of the rocking literature's
    /// minimum overturning accelerations [default: reaches-limit]. Adds a rigid_overturning
    /// column.
    #[arg(long, value_name = "RULE", value_parser = ["reaches-limit", "cannot-return"])]
    pub(crate) rigid_overturning: Option<String>,
    /// Housner's rigid block's own coefficient of restitution (strictly between 0 and 1), the ratio of the rocking
    /// speed after an impact to the speed before it [default: Housner's, 1 - 1.5 sin^2 alpha].
    /// Adds a rigid_restitution column.
    #[arg(long, value_name = "E")]
    pub(crate) rigid_restitution: Option<f64>,
    /// A sweep file (TOML: vary, set, find_min, scan, tol, rigid_form, rigid_overturning,
    /// rigid_restitution); flags add to it.
    #[arg(long)]
    pub(crate) sweep_file: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) store: StoreArgs,
    #[command(flatten)]
    pub(crate) set: SetArgs,
}

/// How a sweep on disk is computed and stored: the flags `sweep` and `fragility` share.
#[derive(clap::Args)]
pub(crate) struct StoreArgs {
    /// Compute only shard K of N of the sweep (disjoint slices of whole chunks), into
    /// OUT/shard-K-of-N (a fragility study's OUT/sweep/shard-K-of-N); set from
    /// SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT in a Slurm job array.
    #[arg(long, value_name = "K/N")]
    pub(crate) shard: Option<String>,
    /// Points per chunk, what a kill can lose (a fragility study's point is a record)
    /// [default: about 1024 simulations' worth].
    #[arg(long)]
    pub(crate) chunk_size: Option<usize>,
    /// Threads, 1 to 1024 [default: one per core].
    #[arg(long)]
    pub(crate) threads: Option<usize>,
    /// Replace the results of another sweep (or a damaged result of this one) in the sweep's
    /// directory instead of refusing them; only the files a sweep writes are removed.
    #[arg(long)]
    pub(crate) force: bool,
    /// No progress bar.
    #[arg(long)]
    pub(crate) quiet: bool,
}

#[derive(clap::Args)]
pub(crate) struct FragilityArgs {
    /// Model file (TOML) with a record excitation (kind = "record"): the body.
    pub(crate) model: PathBuf,
    /// The suite: a directory of record files, a list file (one record a line), or a file
    /// pattern such as 'records/*.AT2'.
    #[arg(long, value_name = "DIR|LIST|PATTERN")]
    pub(crate) records: String,
    /// The intensity measure: pga (g), pgv (m/s), pgd (m), arias (m/s; scales with the square
    /// of the record's factor), cav (m/s), sa (Sa(T, 5 %), g).
    #[arg(long, default_value = "pga")]
    pub(crate) im: String,
    /// The period T of Sa, s [default: the body's pre-uplift period]. With --im sa only.
    #[arg(long, value_name = "T")]
    pub(crate) period: Option<f64>,
    /// The range of excitation.scale searched for each record's smallest overturning scale.
    #[arg(long, value_name = "LO:HI", default_value = "0.1:5")]
    pub(crate) scale: String,
    /// Scales scanned before the bisection [default: 100].
    #[arg(long)]
    pub(crate) scan: Option<usize>,
    /// Width of the final bracket, in scale [default: (HI - LO)/1e4].
    #[arg(long)]
    pub(crate) tol: Option<f64>,
    /// Bootstrap resamples over records for the 5-95 % intervals (0: none).
    #[arg(long, default_value_t = 1000)]
    pub(crate) bootstrap: usize,
    /// Seed of the bootstrap's generator (SplitMix64), reported in fragility.json.
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// Output directory [default: out/<model file stem>-fragility].
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) store: StoreArgs,
    #[command(flatten)]
    pub(crate) figure: FigureArgs,
    #[command(flatten)]
    pub(crate) set: SetArgs,
}

#[derive(Subcommand)]
pub(crate) enum SweepCommand {
    /// Join the outputs of shards (directories of shards, or directories holding
    /// shard-K-of-N directories) into one, exactly as one process writes it; refuses gaps,
    /// overlaps and shards of different sweeps.
    Merge {
        /// Directories of shards, or directories holding shard-K-of-N directories.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
}

/// `--set KEY=VALUE`, any number of times: a model-file key set from the command line.
#[derive(clap::Args)]
pub(crate) struct SetArgs {
    /// Set a model-file key, e.g. --set excitation.amplitude=4.5 (repeatable; checked by the
    /// rules of the file; applied before the other flags).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = Setting::parse)]
    pub(crate) settings: Vec<Setting>,
}

impl SetArgs {
    /// The `--set` keys for the model file `model`: a record path typed here is relative to the
    /// current directory, and is written again relative to the model file, which reads it.
    pub(crate) fn settings_for(self, model: &std::path::Path) -> Vec<Setting> {
        let here = std::env::current_dir().unwrap_or_default();
        self.settings
            .into_iter()
            .map(|s| s.typed_in(&here, Some(model)))
            .collect()
    }

    pub(crate) fn overrides(self, model: &std::path::Path) -> Overrides {
        Overrides {
            settings: self.settings_for(model),
            ..Overrides::default()
        }
    }
}

#[derive(Subcommand)]
pub(crate) enum RecordCommand {
    /// Print what the reader understood (format, header, event, station, component, magnitude,
    /// distance, points, dt, duration, units) and the intensity measures: PGA, PGV, PGD (exact
    /// integrals, peaks between samples included), Arias intensity, CAV, and Sa at --period.
    Info {
        /// The record file (PEER AT2, COSMOS V1/V2, ESM/ITACA, CSV or text).
        file: PathBuf,
        #[command(flatten)]
        options: RecordOptions,
        #[command(flatten)]
        oscillator: OscillatorOptions,
    },
    /// Convert to CSV with columns t,acc_m_s2 (to standard output, or --out FILE).
    Csv {
        /// The record file (PEER AT2, COSMOS V1/V2, ESM/ITACA, CSV or text).
        file: PathBuf,
        #[command(flatten)]
        options: RecordOptions,
        /// Write to this file (atomically) instead of standard output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The metadata and intensity measures of records, one CSV row each (to standard output,
    /// or --out FILE): event, date, station, component, magnitude, distance_km, pga_g, pgv_m_s,
    /// pgd_m, arias_m_s, cav_m_s, sa_g (at --period) and the times of the peaks. A directory or a
    /// list file (*.list: PATH [scale=FACTOR] [vertical=PATH] a line) is a suite of records.
    Intensity {
        /// Record files, directories of records, or list files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        #[command(flatten)]
        options: RecordOptions,
        /// The period of Sa, s [default: none, the sa_g column is left empty].
        #[arg(long, allow_negative_numbers = true)]
        period: Option<f64>,
        /// The damping ratio of Sa's oscillator.
        #[arg(long, default_value_t = flexrock_core::bodies::oscillator::DEFAULT_DAMPING, allow_negative_numbers = true)]
        damping: f64,
        /// Write to this file (atomically) instead of standard output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The pseudo-acceleration response spectrum Sa(T) as CSV (to standard output, or --out
    /// FILE): period_s, damping, sa_g, sa_m_s2, sd_m, t_peak_s, sa_at_samples_g. Sa is the exact
    /// response's peak, between samples included; sa_at_samples_g, the peak over the samples.
    Spectrum {
        /// The record file (PEER AT2, COSMOS V1/V2, ESM/ITACA, CSV or text).
        file: PathBuf,
        #[command(flatten)]
        options: RecordOptions,
        /// Periods, s, separated by commas [default: 0.01 s to 10 s, 20 a decade on a
        /// logarithmic scale].
        #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
        periods: Vec<f64>,
        /// The damping ratio of the oscillators.
        #[arg(long, default_value_t = flexrock_core::bodies::oscillator::DEFAULT_DAMPING, allow_negative_numbers = true)]
        damping: f64,
        /// Write to this file (atomically) instead of standard output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(clap::Args)]
pub(crate) struct RecordOptions {
    /// peer-at2, csv, text, cosmos or esm [default: from the extension, else the first line].
    #[arg(long)]
    pub(crate) format: Option<String>,
    /// Units of the values, for a file whose header does not say them: g, m/s2 or cm/s2 (a
    /// unit that contradicts the file's is refused).
    #[arg(long)]
    pub(crate) units: Option<String>,
    /// Sampling interval of a one-column CSV or text file, s.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) dt: Option<f64>,
}

/// The oscillators of `record info`'s Sa lines.
#[derive(clap::Args)]
pub(crate) struct OscillatorOptions {
    /// Periods of Sa, s, separated by commas [default: none].
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub(crate) period: Vec<f64>,
    /// The damping ratio of Sa's oscillators.
    #[arg(long, default_value_t = flexrock_core::bodies::oscillator::DEFAULT_DAMPING, allow_negative_numbers = true)]
    pub(crate) damping: f64,
}

/// The default lists of `converge` and the reference tolerance, as a user types them; the
/// numbers themselves live in the library.
pub(crate) static DTS_TEXT: LazyLock<String> = LazyLock::new(|| {
    flexrock::writers::list(
        &flexrock::commands::converge::DEFAULT_DTS,
        flexrock::writers::shortest,
    )
});
pub(crate) static RTOLS_TEXT: LazyLock<String> = LazyLock::new(|| {
    flexrock::writers::list(
        &flexrock::commands::converge::DEFAULT_RTOLS,
        flexrock::writers::scientific,
    )
});
