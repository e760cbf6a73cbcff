//! `vcnc sim`: 3-axis material removal on a box, a cylinder or an STL of stock, with a summary
//! (removed volume by tool, cutting time against time in the air, events, the part against a
//! design), an STL of the part and shaded or deviation PNGs.

use super::plot::{each_item, outcome, ViewArg};
use super::run::Format;
use super::{Outcome, SetupError};
use crate::program::Source;
use crate::setup::MachineArgs;
use clap::Args as ClapArgs;
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use vcnc::sim::stock::{self, Cylinder, Mesh};
use vcnc::sim::{mesh, resolution, CutExtents, HeightField, Simulation};
use vcnc::Alarm;

/// The most cells a grid may have: about 200 MB of heights.
const MAX_CELLS: usize = 50_000_000;

/// `vcnc sim` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The program.
    program: PathBuf,
    /// The stock box in program coordinates, mm: xmin,ymin,zmin,xmax,ymax,zmax (default: the
    /// cutting moves' extents, widened by the widest tool's radius and 1 mm, down to 1 mm
    /// below the deepest cut, up to Z0 when the cuts start above it and go below it).
    /// Or `cyl:X,Y,DIAMETER,Z0,Z1`, a cylinder standing on Z (bar stock held in a vice or chuck;
    /// a height field cannot hold one lying down).
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", value_parser = parse_stock, allow_hyphen_values = true, conflicts_with = "stock_stl")]
    stock: Option<StockArg>,
    /// The stock as a solid in an STL file (binary or ASCII), program coordinates, mm: its top
    /// surface above each cell.
    #[arg(long, value_name = "FILE")]
    stock_stl: Option<PathBuf>,
    /// The designed part (STL): report the largest gouge (cut below it) and excess (left above it)
    /// with where they are.
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// With --design: write a top view coloured by deviation (blue gouge, red excess).
    #[arg(long, value_name = "FILE", requires = "design")]
    design_png: Option<PathBuf>,
    /// The default stock's top (without --stock).
    #[arg(long, value_enum, default_value = "part-zero")]
    stock_top: StockTop,
    /// Grid cell, mm (default 0.1, finer on a stock under 20 mm).
    #[arg(long, value_name = "MM")]
    resolution: Option<f64>,
    /// Write the simulated part as binary STL.
    #[arg(long, value_name = "FILE")]
    stl: Option<PathBuf>,
    /// Write a shaded picture of the part.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// The picture's view.
    #[arg(long, value_enum, default_value = "iso")]
    view: ViewArg,
    /// The picture's width, pixels.
    #[arg(long, default_value_t = 1000)]
    width: u32,
    /// Output format of the summary.
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    #[command(flatten)]
    machine: MachineArgs,
}

/// Where the stock taken from the cut's extents has its top.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StockTop {
    /// Z0 when the cuts start above it and go below it, else the highest cutting point.
    PartZero,
    /// The depth the first cutting move reaches (the first pass faces the part).
    FirstCut,
}

/// A stock given on the command line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum StockArg {
    Box([[f64; 3]; 2]),
    Cylinder(Cylinder),
}

fn parse_stock(text: &str) -> Result<StockArg, String> {
    if let Some(rest) = text.strip_prefix("cyl:") {
        let values = numbers(rest)?;
        let [x, y, d, z0, z1] = values[..] else {
            return Err(format!(
                "cyl: expected X,Y,DIAMETER,Z0,Z1, got {} numbers",
                values.len()
            ));
        };
        return if d > 0.0 && z0 < z1 {
            Ok(StockArg::Cylinder(Cylinder {
                center: [x, y],
                diameter: d,
                z: [z0, z1],
            }))
        } else {
            Err("cyl: the diameter must be above 0 and Z0 below Z1".to_string())
        };
    }
    box_stock(text).map(StockArg::Box)
}

fn numbers(text: &str) -> Result<Vec<f64>, String> {
    text.split(',')
        .map(|v| match v.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(format!("`{v}`: not a finite number")),
            Err(e) => Err(format!("`{v}`: {e}")),
        })
        .collect()
}

fn box_stock(text: &str) -> Result<[[f64; 3]; 2], String> {
    let values = numbers(text)?;
    let [x0, y0, z0, x1, y1, z1] = values[..] else {
        return Err(format!("expected six numbers, got {}", values.len()));
    };
    let stock = [[x0, y0, z0], [x1, y1, z1]];
    if (0..3).all(|i| stock[0][i] < stock[1][i]) {
        Ok(stock)
    } else {
        Err("each minimum must be below its maximum".to_string())
    }
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    args.machine.check()?;
    if let Some(r) = args.resolution.filter(|r| !(r.is_finite() && *r > 0.0)) {
        return Err(SetupError::Option {
            option: "--resolution",
            value: r.to_string(),
            expected: "a cell size above 0 mm",
        });
    }
    let source = Source::read(&args.program)?;
    let read_mesh = |path: &PathBuf, option: &'static str| {
        let bytes = std::fs::read(path).map_err(|e| SetupError::Option {
            option,
            value: format!("{}: {e}", path.display()),
            expected: "a readable STL file",
        })?;
        Mesh::parse(&bytes).map_err(|why| SetupError::Option {
            option,
            value: format!("{}: {why}", path.display()),
            expected: "a binary or ASCII STL file",
        })
    };
    let stock_mesh = match &args.stock_stl {
        Some(path) => Some(read_mesh(path, "--stock-stl")?),
        None => None,
    };
    let design = match &args.design {
        Some(path) => Some(read_mesh(path, "--design")?),
        None => None,
    };
    let stock = match (args.stock, &stock_mesh) {
        (Some(StockArg::Box(stock)), _) => Some(stock),
        (Some(StockArg::Cylinder(c)), _) => Some(c.extents()),
        (None, Some(mesh)) => Some(mesh.extents()),
        (None, None) => {
            let mut extents = CutExtents::new();
            extents.per_axis_rapids(&args.machine.machine()?);
            each_item(&source, &args.machine, |item, _| extents.add(item))?;
            match args.stock_top {
                StockTop::PartZero => extents.stock(),
                StockTop::FirstCut => extents.stock_below_first_cut(),
            }
        }
    };
    let Some(stock) = stock else {
        eprintln!(
            "vcnc: {}: no cutting move to take a stock from (give --stock)",
            args.program.display()
        );
        return Ok(Outcome::Clean);
    };
    let cell = resolution(stock, args.resolution, MAX_CELLS);
    let mut simulation = Simulation::on(match (args.stock, &stock_mesh) {
        (Some(StockArg::Cylinder(c)), _) => c.grid(cell),
        (None, Some(mesh)) => stock::stl_grid(mesh, cell),
        _ => HeightField::new(stock, cell),
    });
    simulation.per_axis_rapids(&args.machine.machine()?);
    let (texts, mut alarms) = each_item(&source, &args.machine, |item, timing| {
        simulation.add(item, timing);
    })?;
    let events = simulation.events();
    alarms.extend(events.kept.iter().cloned());
    if let Some(path) = &args.stl {
        let file = std::fs::File::create(path).map_err(SetupError::Output)?;
        let mut out = std::io::BufWriter::new(file);
        mesh::write_stl(simulation.grid(), &mut out)
            .and_then(|()| out.flush())
            .map_err(SetupError::Output)?;
    }
    if let Some(path) = &args.png {
        let bytes = mesh::picture(simulation.grid(), args.view.view(), args.width);
        std::fs::write(path, bytes).map_err(SetupError::Output)?;
    }
    let deviation = design
        .as_ref()
        .map(|d| stock::deviation(simulation.grid(), d));
    if let (Some(path), Some(deviation)) = (&args.design_png, &deviation) {
        // White within a quarter cell (the grid's own uncertainty), full colour at 1 mm.
        let bytes = deviation.picture(cell / 4.0, 1.0, args.width);
        std::fs::write(path, bytes).map_err(SetupError::Output)?;
    }
    let text = match args.format {
        Format::Human => {
            human(args, &simulation, stock, cell)
                + &deviation.as_ref().map_or(String::new(), human_deviation)
        }
        Format::Json => {
            let mut json = to_json(args, &simulation, stock, cell, &texts, &alarms, &events);
            if let Some(deviation) = &deviation {
                let extreme = |e: Option<stock::Extreme>| {
                    e.map_or(
                        serde_json::Value::Null,
                        |e| json!({ "mm": e.amount, "at": e.at }),
                    )
                };
                json["design"] = json!({
                    "gouge": extreme(deviation.gouge),
                    "excess": extreme(deviation.excess),
                });
            }
            format!("{json:#}\n")
        }
    };
    std::io::stdout()
        .write_all(text.as_bytes())
        .map_err(SetupError::Output)?;
    if args.format == Format::Human {
        crate::diagnostics::print_human(&texts, &alarms, crate::diagnostics::Output::Stderr);
    }
    Ok(outcome(&alarms))
}

fn human(args: &Args, simulation: &Simulation, stock: [[f64; 3]; 2], cell: f64) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let grid = simulation.grid();
    let [x, y] = grid.size();
    let [a, b] = stock;
    // Writing into a String cannot fail.
    let _ = writeln!(out, "{}", args.program.display());
    let _ = writeln!(
        out,
        "  stock             X {:.3} .. {:.3}  Y {:.3} .. {:.3}  Z {:.3} .. {:.3}",
        a[0], b[0], a[1], b[1], a[2], b[2]
    );
    let _ = writeln!(out, "  grid              {x} x {y} cells of {cell:.4} mm");
    let _ = writeln!(
        out,
        "  stock volume      {:>14.3} mm^3",
        grid.stock_volume()
    );
    let _ = writeln!(
        out,
        "  removed           {:>14.3} mm^3",
        simulation.removed()
    );
    for t in simulation.tools() {
        let _ = writeln!(
            out,
            "    T{:<4} {:<22} {:>14.3} mm^3  {:>9.1} s cutting",
            t.tool.number,
            t.tool.shape.describe(),
            t.removed,
            t.cutting_seconds
        );
    }
    let times = simulation.times();
    let _ = writeln!(out, "  time cutting      {:>9.1} s", times.cutting);
    let _ = writeln!(out, "  feed in the air   {:>9.1} s", times.feed_in_air);
    let _ = writeln!(out, "  rapid             {:>9.1} s", times.rapid);
    let events = simulation.events();
    let alarms = events.kept.iter().filter(|a| a.is_error()).count();
    let _ = writeln!(
        out,
        "  events            {} alarm(s), {} warning(s)",
        alarms,
        events.kept.len() - alarms
    );
    out
}

fn human_deviation(deviation: &stock::Deviation) -> String {
    let line = |name: &str, e: Option<stock::Extreme>| match e {
        Some(e) => format!(
            "  {name:<17} {:>9.3} mm at X {:.3} Y {:.3} Z {:.3}\n",
            e.amount, e.at[0], e.at[1], e.at[2]
        ),
        None => format!("  {name:<17} none\n"),
    };
    line("largest gouge", deviation.gouge) + &line("largest excess", deviation.excess)
}

fn to_json(
    args: &Args,
    simulation: &Simulation,
    stock: [[f64; 3]; 2],
    cell: f64,
    texts: &crate::diagnostics::Texts,
    alarms: &[Alarm],
    events: &vcnc::sim::SimEvents,
) -> serde_json::Value {
    let grid = simulation.grid();
    let times = simulation.times();
    let tools: Vec<_> = simulation
        .tools()
        .iter()
        .map(|t| {
            json!({
                "tool": t.tool.number,
                "shape": t.tool.shape.describe(),
                "described": t.tool.described,
                "removed_mm3": t.removed,
                "cutting_seconds": t.cutting_seconds,
            })
        })
        .collect();
    let counts: serde_json::Map<String, serde_json::Value> = events
        .counts
        .iter()
        .map(|(code, n)| (code.id().to_string(), json!(n)))
        .collect();
    json!({
        "file": args.program.display().to_string(),
        "stock": { "min": stock[0], "max": stock[1] },
        "resolution_mm": cell,
        "cells": grid.size(),
        "stock_mm3": grid.stock_volume(),
        "removed_mm3": simulation.removed(),
        "remaining_mm3": grid.volume(),
        "tools": tools,
        "time": {
            "cutting_seconds": times.cutting,
            "feed_in_air_seconds": times.feed_in_air,
            "rapid_seconds": times.rapid,
        },
        "event_counts": counts,
        "alarms": alarms.iter().map(|a| crate::diagnostics::to_json(texts, a)).collect::<Vec<_>>(),
    })
}
