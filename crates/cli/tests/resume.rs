//! An ensemble interrupted midway (kill -9, or Ctrl-C) resumes and ends with the same tables as
//! an uninterrupted run.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use stickslip_support::{assert_same_tables, scratch_dir};

const PIPELINE: &str = r#"
version = 1
name = "resume"
[seeds]
range = { first = 1, count = 16 }
[shear]
duration_s = 0.12
[record]
interval_s = 5e-5
[[record.control]]
nodes = [36]
components = ["z"]
"#;

fn stickslip(dir: &Path, out: &str, threads: &str) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stickslip"));
    c.args(["pipeline", "p.toml", "--out", out, "--threads", threads, "--quiet"]).current_dir(dir);
    c
}

/// Finished seeds: `runs` parts (a killed writer may leave a hidden temporary file beside them).
fn finished(dir: &Path) -> usize {
    std::fs::read_dir(dir.join("tables/runs"))
        .map(|d| d.flatten().filter(|e| e.path().extension().is_some_and(|x| x == "parquet")).count())
        .unwrap_or(0)
}

/// Starts an ensemble on one thread and returns it once `n` seeds are finished.
fn start_and_wait(dir: &Path, out: &str, n: usize) -> Child {
    let mut child = stickslip(dir, out, "1").stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    while finished(&dir.join(out)) < n {
        // However slow the machine, the ensemble is still running until it has n seeds; one that
        // ended before that failed.
        if let Some(status) = child.try_wait().unwrap() {
            assert!(finished(&dir.join(out)) >= n, "the ensemble ended ({status}) before {n} seeds were finished");
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    child
}

fn complete(dir: &Path, out: &str) -> String {
    let o = stickslip(dir, out, "2").output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn killed_or_interrupted_ensembles_resume_to_the_same_tables() {
    let dir = scratch_dir("resume");
    std::fs::write(dir.join("p.toml"), PIPELINE).unwrap();
    let stdout = complete(&dir, "full");
    assert!(stdout.contains("16 seeds (16 run now, 0 already done, 0 failed)"), "{stdout}");

    // kill -9 midway.
    let mut child = start_and_wait(&dir, "killed", 4);
    child.kill().unwrap();
    child.wait().unwrap();
    let done = finished(&dir.join("killed"));
    assert!(done < 16, "the ensemble finished before it could be killed");
    let stdout = complete(&dir, "killed");
    let leftovers: Vec<_> = stickslip_support::files_under(&dir.join("killed"))
        .into_iter()
        .filter(|p| p.to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left behind: {leftovers:?}");
    assert!(stdout.contains(&format!("({} run now, {done} already done", 16 - done)), "{stdout}");
    assert_same_tables(&dir.join("full"), &dir.join("killed"), &["wall_time_s"]);

    // Ctrl-C midway: the finished seeds are kept and the exit says how to resume.
    let child = start_and_wait(&dir, "interrupted", 4);
    let status = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("interrupted:") && err.contains("run the same command again to resume"), "{err}");
    let done = finished(&dir.join("interrupted"));
    assert!((4..16).contains(&done));
    complete(&dir, "interrupted");
    assert_same_tables(&dir.join("full"), &dir.join("interrupted"), &["wall_time_s"]);
}
