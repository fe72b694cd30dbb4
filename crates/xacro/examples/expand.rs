//! Print the expansion of a xacro file, for debugging and timing.
//!
//! ```text
//! cargo run --release -p urdf-validator-xacro --example expand -- FILE [name:=value ...] [--package-path DIR]... [--banner]
//!     [--origins] [--repeat N]
//! ```
//! `--origins` prints, after the XML, the source location of every start tag; `--repeat N` expands N times
//! and prints the median wall time and the mean CPU time to stderr instead of the XML.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// CPU time (user + system) of this process so far, from `/proc/self/stat` (Linux; clock ticks of 10 ms).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let mut opts = xacro::Options::default();
    let mut file = None;
    let mut origins = false;
    let mut repeat = 0usize;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--package-path" => opts.package_paths.extend(args.next().map(PathBuf::from)),
            "--banner" => opts.banner = true,
            "--origins" => origins = true,
            "--repeat" => repeat = args.next().and_then(|n| n.parse().ok()).unwrap_or(1),
            _ => match xacro::parse_arg(&a) {
                Some(kv) => opts.args.push(kv),
                None => file = Some(PathBuf::from(a)),
            },
        }
    }
    let Some(file) = file else {
        eprintln!("usage: expand FILE [name:=value ...] [--package-path DIR] [--banner] [--origins] [--repeat N]");
        return ExitCode::from(2);
    };
    if repeat > 0 {
        let cpu_start = cpu_seconds();
        let mut times = Vec::with_capacity(repeat);
        for _ in 0..repeat {
            let t = Instant::now();
            if let Err(e) = xacro::expand_file(&file, &opts) {
                eprintln!("{e}");
                return ExitCode::from(2);
            }
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        eprintln!(
            "median {:.3} ms over {repeat} runs",
            times[repeat / 2] * 1e3
        );
        if let (Some(start), Some(end)) = (cpu_start, cpu_seconds()) {
            eprintln!("cpu {:.3} ms per run", (end - start) / repeat as f64 * 1e3);
        }
        return ExitCode::SUCCESS;
    }
    match xacro::expand_file(&file, &opts) {
        Ok(x) => {
            print!("{}", x.xml);
            for w in &x.warnings {
                match &w.location {
                    Some(l) => eprintln!("warning: {l}: {}", w.message),
                    None => eprintln!("warning: {}", w.message),
                }
            }
            if origins {
                for e in x
                    .map
                    .entries()
                    .iter()
                    .filter(|e| e.piece == xacro::Piece::StartTag)
                {
                    let Some(origin) = x.map.origins().get(e.origin) else {
                        continue;
                    };
                    let tag = x.xml.get(e.output.clone()).unwrap_or("");
                    let loc = x
                        .location(origin)
                        .map(|l| l.to_string())
                        .unwrap_or_default();
                    let stack: Vec<String> = x
                        .map
                        .stack(origin)
                        .map(|f| {
                            let at = x.sources.get(f.file).map(|s| {
                                let (l, c) = s.line_col(f.span.start);
                                format!("{}:{l}:{c}", s.path.display())
                            });
                            format!("{:?} {} at {}", f.kind, f.name, at.unwrap_or_default())
                        })
                        .collect();
                    println!(
                        "{loc}  {}  [{}]",
                        tag.chars().take(60).collect::<String>(),
                        stack.join(" <- ")
                    );
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
