//! The `conformap` binary: parses the command line, runs the command, prints what it
//! returns (the only place that prints) and exits with its code.
//!
//! Exit codes: 0 success, 1 bad input, 2 usage error, 3 numerical failure, 4 some inputs of
//! a batch failed. Progress (a spinner, a batch's bar) is drawn on stderr only when it is a
//! terminal and the work takes over a second; `--quiet` turns it and the summary line off.

use std::io::Write;
use std::process::ExitCode;

use std::sync::Arc;

use conformap::pipeline::context::RunContext;
use conformap_cli::progress::{BarWatcher, Progress, ProgressMode};
use conformap_cli::{Cli, Command};

fn main() -> ExitCode {
    let cli = Cli::try_parse_args(std::env::args_os()).unwrap_or_else(|e| e.exit());
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
