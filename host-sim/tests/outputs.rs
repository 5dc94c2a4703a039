//! Outputs never clobber (issue 33, item 1): every file host-sim writes is renamed into place from a
//! temporary file beside it, and only onto a new path or a regular file. A directory, a FIFO or a link to
//! a FIFO at the target is exit 1 with a message naming the path, the target untouched and no temporary
//! file left behind.

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{BIN, TempDir};

const CATALOGUE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/catalogue_leo.tle");
const RADARS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_radar.json");
const FIXTURE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/hand_written.json");

fn describe(output: &Output) -> String {
    format!(
        "status {:?}\nstdout:\n{}\nstderr:\n{}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// Runs host-sim with `args`, killed after a minute: opening a FIFO for writing blocks until a reader
/// comes, so a writer that does not check its target would hang.
fn host_sim(args: &[&std::ffi::OsStr]) -> Output {
    let mut child =
        Command::new(BIN).args(args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("run host-sim");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            let output = child.wait_with_output().expect("output");
            panic!("host-sim {args:?} still running after 60 s (blocked on its output?)\n{}", describe(&output));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

fn generate_catalogue(out: &Path) -> Output {
    let args = ["generate", "catalogue", "--catalogue", CATALOGUE, "--sensors", RADARS, "--start"];
    let mut args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_ref()).collect();
    args.extend(["2026-03-20T00:00:00Z", "--duration-hours", "0.1", "--out"].map(std::ffi::OsStr::new));
    args.push(out.as_os_str());
    host_sim(&args)
}

fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().expect("mkfifo");
    assert!(status.success(), "mkfifo {}", path.display());
}

fn is_fifo(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_fifo())
}

/// Names in `dir` (not recursive) that look like a temporary output.
fn leftovers(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().contains("partial")))
        .collect()
}

/// Exit 1, one `error:` line naming `target` and saying what it is (besides the truth-free judge's
/// `warning: sensor` lines, written before the summary).
fn assert_refused(output: &Output, target: &Path, what: &str) {
    let stderr: String = String::from_utf8_lossy(&output.stderr)
        .lines()
        .filter(|l| !l.starts_with("warning: sensor "))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(output.status.code(), Some(1), "{}", describe(output));
    assert!(stderr.starts_with("error: ") && stderr.lines().count() == 1, "{}", describe(output));
    assert!(stderr.contains(&*target.to_string_lossy()) && stderr.contains(what), "{}", describe(output));
}

#[test]
fn generate_catalogue_refuses_a_directory_and_leaves_it_untouched() {
    let dir = TempDir::new("out-dir");
    let target = dir.join("scenario.json");
    std::fs::create_dir(&target).expect("mkdir");
    std::fs::write(target.join("keep.txt"), "kept").expect("write");
    let output = generate_catalogue(&target);
    assert_refused(&output, &target, "a directory");
    assert_eq!(std::fs::read_to_string(target.join("keep.txt")).expect("kept"), "kept");
    assert!(leftovers(&dir.0).is_empty(), "{:?}", leftovers(&dir.0));
}

#[test]
fn generate_catalogue_refuses_a_fifo_and_a_link_to_one() {
    let dir = TempDir::new("out-fifo");
    let fifo = dir.join("scenario.json");
    mkfifo(&fifo);
    assert_refused(&generate_catalogue(&fifo), &fifo, "a FIFO");
    assert!(is_fifo(&fifo), "the FIFO was replaced");
    let link = dir.join("link.json");
    std::os::unix::fs::symlink(&fifo, &link).expect("symlink");
    assert_refused(&generate_catalogue(&link), &link, "a link to a FIFO");
    assert!(std::fs::symlink_metadata(&link).expect("link").file_type().is_symlink(), "the link was replaced");
    assert!(is_fifo(&fifo), "the FIFO was replaced");
    assert!(leftovers(&dir.0).is_empty(), "{:?}", leftovers(&dir.0));
}

#[test]
fn generate_catalogue_replaces_a_regular_file_and_a_link_to_one() {
    let dir = TempDir::new("out-regular");
    let target = dir.join("scenario.json");
    std::fs::write(&target, "old").expect("write");
    let output = generate_catalogue(&target);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let text = std::fs::read_to_string(&target).expect("scenario");
    assert!(text.starts_with('{') && text.contains("rfisst-scenario/2"), "not replaced: {:.80}", text);
    // A link to a regular file: the link is replaced by the new file, the file it named is left alone.
    let named = dir.join("named.json");
    std::fs::write(&named, "named").expect("write");
    let link = dir.join("link.json");
    std::os::unix::fs::symlink(&named, &link).expect("symlink");
    let output = generate_catalogue(&link);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    assert!(std::fs::symlink_metadata(&link).expect("link").file_type().is_file());
    assert_eq!(std::fs::read_to_string(&named).expect("named"), "named");
    assert!(leftovers(&dir.0).is_empty(), "{:?}", leftovers(&dir.0));
}

#[test]
fn the_other_writers_refuse_a_fifo_too() {
    let dir = TempDir::new("out-others");
    // A planar scenario (generate), a JSON report (sgp4-check), a TDM export: each onto a FIFO.
    let fifo = dir.join("fifo");
    mkfifo(&fifo);
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    let runs: Vec<Vec<&std::ffi::OsStr>> = vec![
        vec![os("generate"), os("linear-small"), os("--out"), fifo.as_os_str()],
        vec![os("sgp4-check"), os("--out"), fifo.as_os_str()],
        vec![os("catalogue"), os(CATALOGUE), os("--out"), fifo.as_os_str()],
    ];
    for args in runs {
        let output = host_sim(&args);
        assert_refused(&output, &fifo, "a FIFO");
        assert!(is_fifo(&fifo), "{args:?}: the FIFO was replaced");
    }
    assert!(leftovers(&dir.0).is_empty(), "{:?}", leftovers(&dir.0));
}

#[test]
fn run_refuses_a_fifo_among_its_streamed_outputs() {
    // scans.jsonl and estimates.csv are streamed to a temporary file: a FIFO in their place is refused
    // before the run starts, and it stays a FIFO.
    for name in ["scans.jsonl", "estimates.csv", "summary.json"] {
        let dir = TempDir::new("out-run");
        let out = dir.join("out");
        std::fs::create_dir(&out).expect("mkdir");
        let fifo = out.join(name);
        mkfifo(&fifo);
        let os = std::ffi::OsStr::new;
        let output = host_sim(&[os("run"), os(FIXTURE), os("--quiet"), os("--out"), out.as_os_str()]);
        assert_refused(&output, &fifo, "a FIFO");
        assert!(is_fifo(&fifo), "{name}: the FIFO was replaced");
        assert!(leftovers(&out).is_empty(), "{name}: {:?}", leftovers(&out));
    }
}
