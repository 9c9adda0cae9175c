//! The `fepre` command line; see `fepre --help`. It parses, calls the library's public API
//! (one call per subcommand) and prints.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
