//! The `conformap` binary: parses the command line, runs the command, prints what it
//! returns (the only place that prints) and exits with its code.
//!
//! Exit codes: 0 success, 1 bad input, 2 usage error, 3 numerical failure, 4 some inputs of
//! a batch failed. Progress (a spinner, a batch's bar) is drawn on stderr only when it is a
//! terminal and the work takes over a second; `--quiet` turns it and the summary line off.
//! SIGINT and SIGTERM remove every staged output and exit with 130 and 143 (128 + the
//! signal), so an interrupted run leaves neither outputs nor staging files.

use std::io::Write;
use std::process::ExitCode;

use std::sync::Arc;

use conformap::pipeline::context::RunContext;
use conformap_cli::progress::{BarWatcher, Progress, ProgressMode};
use conformap_cli::{Cli, Command};

fn main() -> ExitCode {
    let cli = Cli::try_parse_args(std::env::args_os()).unwrap_or_else(|e| e.exit());
    #[cfg(unix)]
    watch_signals();
    let mode = ProgressMode::detect(cli.quiet);
    let result = match &cli.command {
        Command::Batch(args) => {
            // JSON lines as they come (a closed pipe is not worth a panic)
            let mut sink = |line: &str| {
                let _ = writeln!(std::io::stdout().lock(), "{line}");
            };
            conformap_cli::cli::batch_job(args).and_then(|job| {
                let progress = Progress::bar(mode, 0);
                let context = RunContext {
                    watcher: Some(Arc::new(BarWatcher(progress.bar_handle().clone()))),
                    budget: None,
                };
                context.scope(|| conformap::batch::run_streaming(&job, &mut sink))
            })
        }
        command => {
            let progress = Progress::spinner(mode);
            let context = RunContext {
                watcher: Some(Arc::new(BarWatcher(progress.bar_handle().clone()))),
                budget: None,
            };
            context.scope(|| command.run())
        }
    };
    match result {
        Ok(outcome) => {
            if let Some(text) = &outcome.stdout {
                // a closed pipe (`conformap info m.obj | head`) is not worth a panic
                let _ = writeln!(std::io::stdout().lock(), "{text}");
            }
            if !cli.quiet {
                for line in &outcome.messages {
                    eprintln!("{line}");
                }
            }
            ExitCode::from(outcome.exit_code)
        }
        Err(failure) => {
            eprintln!("error: {failure}");
            if let Some(hint) = failure.hint() {
                eprintln!("hint: {hint}");
            }
            ExitCode::from(failure.exit_code())
        }
    }
}

/// Watches SIGINT and SIGTERM on a thread of their own: on the first, the staged outputs
/// are removed ([`conformap::pipeline::staging::abandon_staged`], which also stops any
/// commit) and the process exits with 128 + the signal. Without the handler (it could not
/// be installed) the signals keep their default action.
#[cfg(unix)]
fn watch_signals() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let removed = conformap::pipeline::staging::abandon_staged();
            let name = if signal == SIGINT {
                "SIGINT"
            } else {
                "SIGTERM"
            };
            eprintln!(
                "error: interrupted by {name}: {removed} staged file(s) removed; no output \
                 is left half-written"
            );
            std::process::exit(128 + signal);
        }
    });
}
