//! `evhi show`: a scenario and the paper's hypotheses for it.

use evhi::scenario::Scenario;

#[derive(clap::Args)]
pub struct ShowArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(value_parser = evhi::scenario::arg_parser())]
    pub scenario: String,
    /// Contact segments n = 1/h of the run to check (a multiple of 4; default 64).
    /// Refused on a mesh scene, whose mesh is its file's.
    #[arg(long, allow_hyphen_values = true)]
    pub n: Option<usize>,
    /// Time steps N of the run to check (default 64, as `solve`; a scenario with
    /// problem = "steady" is one solve, 1 step, the only value accepted).
    #[arg(long, allow_hyphen_values = true)]
    pub steps: Option<usize>,
}

/// Prints the report; a failed hypothesis is a warning, not an error.
pub fn run(args: ShowArgs) -> Result<(), Box<dyn std::error::Error>> {
    let scn = Scenario::load(&args.scenario)?;
    // Refused as `solve` refuses them, by their options.
    let flag = super::solve::settings_flag;
    if let Some(n) = args.n {
        scn.refuse_level_on_mesh(n)
            .map_err(|e| e.for_flag("n", "--n"))?;
    }
    let n = match scn.body() {
        Some(body) => body.gamma3.len() - 1,
        None => {
            let n = args.n.unwrap_or(64);
            evhi::mesh::check_n(n).map_err(flag)?;
            evhi::scheme::check_memory(n, evhi::mesh::rows(n, scn.geometry())).map_err(flag)?;
            n
        }
    };
    // The step count `solve` would take, refused as `solve` refuses it.
    let steps = args
        .steps
        .unwrap_or_else(|| evhi::simulation::default_steps(&scn));
    evhi::scheme::check_steps(Some(&scn), &evhi::scheme::Settings::new(n, steps)).map_err(|e| {
        match e {
            evhi::scheme::RunError::Input(e) => evhi::scheme::RunError::Input(flag(e)),
            other => other,
        }
    })?;
    let (text, warnings) = evhi::show::report(&scn, n, steps);
    evhi::term::emit(&text)?;
    if warnings > 0 {
        evhi::diag!("{warnings} warning(s)");
    }
    Ok(())
}
