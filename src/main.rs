//! TrochoPlan: `trochoplan` with no subcommand opens the planner window on the built-in
//! default job; subcommands (`analyze`, `sweep`, `export`) run headless and never touch a display.

mod app;
mod cli;
mod shared;
mod worker;

#[cfg(test)]
mod layout_tests;

use std::process::ExitCode;

fn main() -> ExitCode {
    if std::env::args_os().len() <= 1 {
        return match app::run(trochoplan_core::Job::default()) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("trochoplan: cannot open the window: {e}");
                ExitCode::FAILURE
            }
        };
    }
    cli::main()
}
