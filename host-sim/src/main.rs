//! The `host-sim` command line: parses the arguments and runs the command ([`host_sim::commands`]) on a
//! thread with a large stack; the exit codes are [`host_sim::commands`]'s.

use clap::Parser;
use host_sim::commands::{Cli, execute};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    // The host profile's tracker holds several MiB inline: run on a thread with a large stack.
    let worker = std::thread::Builder::new().stack_size(512 << 20).spawn(move || execute(cli));
    let outcome = match worker {
        Ok(handle) => handle.join(),
        Err(e) => {
            eprintln!("error: cannot start the worker thread: {e}");
            return ExitCode::from(1);
        }
    };
    match outcome {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
        Err(_) => {
            eprintln!("error: internal failure (a panic); please report it with the scenario file");
            ExitCode::from(1)
        }
    }
}
