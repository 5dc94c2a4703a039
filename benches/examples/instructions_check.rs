//! Compares the instruction counts of the gungraun benches (`--output-format=json`, one summary per line)
//! with the committed baseline, and fails when one grew by more than the baseline's tolerance.
//!
//! ```text
//! cargo run --release -p benches --example instructions_check -- BASELINE COUNTS [--update]
//! ```
//!
//! Exit status: 0 when every benchmark of the baseline was measured and none grew beyond the tolerance;
//! 1 otherwise (also for a benchmark missing from either side). `--update` rewrites the baseline from the
//! counts instead (keeping its tolerance). `scripts/instructions-check.sh` runs the benches and this.
use serde_json::{Map, Value, json};
use std::collections::BTreeMap;
use std::process::{Command, ExitCode};

/// Default tolerance (percent) for a new baseline.
const TOLERANCE_PERCENT: f64 = 2.0;

/// `group::function::id` → instructions (callgrind's Ir), from gungraun's JSON lines.
fn read_counts(text: &str) -> Result<BTreeMap<String, u64>, String> {
    let mut counts = BTreeMap::new();
    for (index, line) in text.lines().enumerate().filter(|(_, line)| line.trim_start().starts_with('{')) {
        let summary: Value = serde_json::from_str(line).map_err(|e| format!("line {}: {e}", index + 1))?;
        let module = summary["module_path"].as_str().unwrap_or_default();
        // "instructions::<group>::<function>" → "<group>::<function>"
        let module = module.split_once("::").map_or(module, |(_, rest)| rest);
        let id = summary["id"].as_str().unwrap_or_default();
        let ir = summary["profiles"]
            .as_array()
            .and_then(|profiles| profiles.iter().find(|p| p["tool"] == "Callgrind"))
            .and_then(|profile| profile["data"]["total"]["metrics"]["Ir"]["values"]["new"].as_u64())
            .ok_or_else(|| format!("line {}: no callgrind Ir for {module} {id}", index + 1))?;
        counts.insert(format!("{module}::{id}"), ir);
    }
    if counts.is_empty() {
        return Err("no benchmark summary in the counts file".into());
    }
    Ok(counts)
}

/// First line of `program --version`, or "unknown".
fn version(program: &str) -> String {
    Command::new(program)
        .arg("--version")
        .output()
        .ok()
        .and_then(|out| String::from_utf8(out.stdout).ok())
        .and_then(|text| text.lines().next().map(str::to_string))
        .unwrap_or_else(|| "unknown".into())
}

fn environment() -> Value {
    json!({
        "rustc": version("rustc"),
        "valgrind": version("valgrind"),
        "gungraun_runner": version("gungraun-runner"),
        "arch": std::env::consts::ARCH,
    })
}

fn run() -> Result<bool, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let update = args.iter().any(|a| a == "--update");
    let paths: Vec<&String> = args.iter().filter(|a| !a.starts_with("--")).collect();
    let [baseline_path, counts_path] = paths[..] else {
        return Err("usage: instructions_check BASELINE COUNTS [--update]".into());
    };
    let counts_text = std::fs::read_to_string(counts_path).map_err(|e| format!("{counts_path}: {e}"))?;
    let counts = read_counts(&counts_text).map_err(|e| format!("{counts_path}: {e}"))?;
    let old: Option<Value> = std::fs::read_to_string(baseline_path)
        .ok()
        .map(|text| serde_json::from_str(&text).map_err(|e| format!("{baseline_path}: {e}")))
        .transpose()?;
    let tolerance = old.as_ref().and_then(|b| b["tolerance_percent"].as_f64()).unwrap_or(TOLERANCE_PERCENT);

    if update {
        let instructions: Map<String, Value> = counts.iter().map(|(k, v)| (k.clone(), json!(v))).collect();
        let baseline = json!({
            "description": "Instruction counts (callgrind Ir) of benches/benches/instructions.rs; checked by scripts/instructions-check.sh, which fails when a count exceeds its baseline by more than tolerance_percent. Refresh with scripts/instructions-check.sh --update after an intended change.",
            "tolerance_percent": tolerance,
            "environment": environment(),
            "instructions": instructions,
        });
        let text = serde_json::to_string_pretty(&baseline).map_err(|e| e.to_string())?;
        std::fs::write(baseline_path, format!("{text}\n")).map_err(|e| format!("{baseline_path}: {e}"))?;
        println!("wrote {baseline_path} ({} benchmarks)", counts.len());
        return Ok(true);
    }

    let baseline = old.ok_or_else(|| format!("{baseline_path}: missing (create it with --update)"))?;
    let expected = baseline["instructions"].as_object().ok_or_else(|| format!("{baseline_path}: no instructions"))?;
    let now = environment();
    if baseline["environment"]["rustc"] != now["rustc"] || baseline["environment"]["valgrind"] != now["valgrind"] {
        println!(
            "note: baseline measured with {} / {}, now {} / {}: counts may shift with the toolchain",
            baseline["environment"]["rustc"], baseline["environment"]["valgrind"], now["rustc"], now["valgrind"]
        );
    }
    let mut ok = true;
    println!("{:<44} {:>14} {:>14} {:>9}  (tolerance +{tolerance}%)", "benchmark", "baseline", "now", "change");
    for (name, base) in expected {
        let base = base.as_u64().ok_or_else(|| format!("{baseline_path}: {name} is not a count"))?;
        let Some(&count) = counts.get(name) else {
            println!("{name:<44} {base:>14} {:>14} {:>9}  FAIL: not measured", "-", "-");
            ok = false;
            continue;
        };
        let change = (count as f64 / base as f64 - 1.0) * 100.0;
        let verdict = if change > tolerance {
            ok = false;
            "FAIL: grew beyond the tolerance"
        } else if change < -tolerance {
            "improved: refresh the baseline (--update)"
        } else {
            "ok"
        };
        println!("{name:<44} {base:>14} {count:>14} {change:>+8.2}%  {verdict}");
    }
    for name in counts.keys().filter(|name| !expected.contains_key(*name)) {
        println!("{name:<44} {:>14} {:>14} {:>9}  FAIL: not in the baseline (--update)", "-", counts[name], "-");
        ok = false;
    }
    Ok(ok)
}

fn main() -> ExitCode {
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => {
            eprintln!("instruction counts: FAILED (see the table above)");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
