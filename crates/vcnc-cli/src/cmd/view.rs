//! `vcnc view`: the toolpath in 3D in a local page, with the planner's timeline, the block of
//! each segment and the simulated stock with its alarms; written as one self-contained HTML
//! file (`--html`) or served on 127.0.0.1 until the process is stopped.

use super::plot::{each_item, outcome};
use super::{Outcome, SetupError};
use crate::program::Source;
use crate::setup::MachineArgs;
use crate::view::{page, scene::Scene, serve};
use clap::Args as ClapArgs;
use std::path::PathBuf;
use vcnc::sim::{resolution, CutExtents, HeightField, Simulation};

/// The most cells of the simulated grid, as `vcnc sim` allows.
const MAX_CELLS: usize = 50_000_000;

/// `vcnc view` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The program.
    program: PathBuf,
    /// Write the page to FILE (one self-contained HTML file) instead of serving it.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    /// Serve on this port of 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 0, conflicts_with = "html")]
    port: u16,
    /// Leave out the simulated stock (a box from the cut's extents, as `vcnc sim` takes it).
    #[arg(long)]
    no_stock: bool,
    #[command(flatten)]
    machine: MachineArgs,
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    args.machine.check()?;
    let machine = args.machine.machine()?;
    let source = Source::read(&args.program)?;
    let stock = if args.no_stock {
        None
    } else {
        let mut extents = CutExtents::new();
        extents.per_axis_rapids(&machine);
        each_item(&source, &args.machine, |item, _| extents.add(item))?;
        extents.stock()
    };
    let mut simulation = stock.map(|stock| {
        let cell = resolution(stock, None, MAX_CELLS);
        let mut simulation = Simulation::on(HeightField::new(stock, cell));
        simulation.per_axis_rapids(&machine);
        simulation
    });
    let mut scene = Scene::new(&machine);
    let (texts, mut alarms) = each_item(&source, &args.machine, |item, timing| {
        scene.add(item, timing, simulation.as_ref().map(Simulation::grid));
        if let Some(simulation) = &mut simulation {
            simulation.add(item, timing);
        }
    })?;
    if let Some(simulation) = &simulation {
        alarms.extend(simulation.events().kept);
    }
    let name = args.program.display().to_string();
    let data = scene.to_json(
        &name,
        &texts,
        simulation.as_ref().map(Simulation::grid),
        &alarms,
    );
    let html = page::html(&data);
    crate::diagnostics::print_human(&texts, &alarms, crate::diagnostics::Output::Stderr);
    if let Some(path) = &args.html {
        std::fs::write(path, html).map_err(SetupError::Output)?;
        return Ok(outcome(&alarms));
    }
    let listener = serve::bind(args.port).map_err(|e| SetupError::Option {
        option: "--port",
        value: format!("{}: {e}", args.port),
        expected: "a free port on 127.0.0.1",
    })?;
    let address = listener.local_addr().map_err(SetupError::Output)?;
    println!("vcnc: viewing {name} at http://{address}/ (Ctrl-C stops)");
    serve::serve(&listener, &html);
    Ok(outcome(&alarms))
}
