//! `stickslip`: the command line. Glue only: each subcommand (one file in `commands/`) parses
//! its arguments, calls the crates that do the work and prints what they return.

#[macro_use]
mod text;
mod commands;
#[cfg(feature = "mpi")]
mod mpi_ranks;
mod progress;
#[cfg(feature = "mpi")]
mod split;

use clap::{Parser, Subcommand};

use commands::{catalogue, check, compare, gmm, merge, per_seed, pipeline, run, select, show, similarity, spectra};

/// Earthquake stick-slip with the Lattice Discrete Element Method: simulate ensembles of seeds and
/// turn them into event catalogues, accelerograms, spectra, statistics and scaled magnitudes.
///
/// The model, its equations and conventions: docs/model.md in the repository.
#[derive(Parser, Debug)]
#[command(name = "stickslip", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a pipeline's seeds in parallel and write every table and the report (resumable).
    Pipeline(pipeline::Args),
    /// Run one seed of a pipeline (an ensemble of one: the same tables and report).
    Run(run::Args),
    /// Check that every shard of an ensemble is in an output folder and gather its tables,
    /// statistics and report.
    Merge(merge::Args),
    /// Compare the tables of two output folders (wall times ignored); exit 1 if they differ.
    Compare(compare::Args),
    /// Check a pipeline file and print what it builds (nothing is run).
    Check(check::Args),
    /// Print the schema and first rows of a Parquet table (or every part matching a glob).
    Show(show::Args),
    /// One main shock seed by seed (stress drop, duration, recurrence, magnitude, normal-stress
    /// range) as a Markdown table: the README's calibration table.
    Seeds(per_seed::Args),
    /// Scale a model event to a prototype fault (docs/model.md §9) and print the numbers.
    Similarity(similarity::Args),
    /// Response spectra, Fourier spectrum and intensity measures of an accelerogram file (PEER
    /// .AT2, or CSV with time and acceleration columns).
    Spectra(spectra::Args),
    /// Choose a set of an ensemble's records matched to a design spectrum (ASCE 7, EC8 or a CSV
    /// target), scaled, and write it under <folder>/set/.
    Select(select::Args),
    /// Catalogue statistics of an ensemble: Gutenberg–Richter b-values, recurrence CV and
    /// renewal fits, Omori–Utsu aftershock decay, scaling exponents (rewrites their tables).
    Catalogue(catalogue::Args),
    /// A fault scenario's stations against the NGA-West2 ground-motion models BSSA14, ASK14, CB14, CY14:
    /// residuals of RotD50 PGA, PGV and PSA, bias per site and period, the Part-B test, as tables and a figure.
    Gmm(gmm::Args),
}

fn main() {
    let command = Cli::parse().command;
    // Output piped into `head` and the like. A command that only reads ends quietly when the
    // reader goes away, as Unix tools do; one that writes tables, records or a report keeps
    // going (SIGPIPE stays ignored and its prints ignore the broken pipe, see `text::outln`)
    // so that a closed pipe never leaves its outputs half written.
    let only_reads = matches!(
        command,
        Command::Check(_) | Command::Show(_) | Command::Seeds(_) | Command::Similarity(_) | Command::Compare(_)
    );
    #[cfg(unix)]
    if only_reads {
        // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
        unsafe {
            libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        }
    }
    // Under mpirun/srun (the `mpi` feature), `pipeline` splits every seed over the ranks: rank 0
    // runs the command, the others follow its seeds and are done when it is.
    #[cfg(feature = "mpi")]
    let mut command = command;
    #[cfg(feature = "mpi")]
    let role = match &mut command {
        Command::Pipeline(a) => match split::start(&a.pipelines, &mut a.threads) {
            Ok(split::Role::Follower) => return,
            Ok(role) => Some(role),
            Err(e) => {
                errln!("error: {e:#}");
                std::process::exit(1);
            }
        },
        _ => None,
    };
    let result = match command {
        Command::Pipeline(a) => pipeline::run(a),
        Command::Run(a) => run::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Check(a) => check::run(a),
        Command::Show(a) => show::run(a),
        Command::Seeds(a) => per_seed::run(a),
        Command::Similarity(a) => similarity::run(a),
        Command::Spectra(a) => spectra::run(a),
        Command::Select(a) => select::run(a),
        Command::Catalogue(a) => catalogue::run(a),
        Command::Gmm(a) => gmm::run(a),
    };
    // Rank 0 tells the other ranks the command is over before it exits.
    #[cfg(feature = "mpi")]
    drop(role);
    if let Err(e) = result {
        errln!("error: {e:#}");
        std::process::exit(1);
    }
}
