//! The `conformap` binary: parses the command line, runs the command, prints what it
//! returns (the only place that prints) and exits with its code.
//!
//! Exit codes: 0 success, 1 bad input, 2 usage error, 3 numerical failure.

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;
use conformap_cli::Cli;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command.run() {
        Ok(outcome) => {
            if let Some(text) = &outcome.stdout {
                // a closed pipe (`conformap info m.obj | head`) is not worth a panic
                let _ = writeln!(std::io::stdout().lock(), "{text}");
            }
            for line in &outcome.messages {
                eprintln!("{line}");
            }
            ExitCode::SUCCESS
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
