//! The `fepre` command line; see `fepre --help`.

fn main() -> std::process::ExitCode {
    fepre::cli::main()
}
