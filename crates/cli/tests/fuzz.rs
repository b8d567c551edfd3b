//! The front door under fuzzing: mutants of every shipped pipeline (NaN, ±inf, 1e400, −0.0,
//! subnormals, huge integers, values scaled by powers of ten, wrong types, deleted, duplicated
//! and unknown keys, injected sections, unicode and long strings, input files that are FIFOs,
//! devices, folders, climbing paths or bad CSV) go through `stickslip check`, and the accepted
//! ones through a `stickslip run` bounded in wall time. Nothing may panic, hang (outlive its
//! bound by more than the grace an interrupt gets), write a NaN or an infinity into a table,
//! print a number of 25 digits, or refuse without naming the field.
//!
//! `fuzz_every_shipped_pipeline` is the suite's seeded run (a few hundred mutants, about a
//! half a minute on 2 cores); `fuzz_long` (ignored; `scripts/fuzz.sh`) is the long one whose figures are
//! in docs/guide/refusals.md: `STICKSLIP_FUZZ_MUTANTS`, `STICKSLIP_FUZZ_RUNS`, `STICKSLIP_FUZZ_SEED`.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use stickslip_support::{parquet_files, read_table, repo_path, scratch_dir};

/// splitmix64: a small seeded generator, the same mutants on every machine.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
}

/// The top-level keys of a pipeline file: a refusal must name a field under one of them.
const TOP_KEYS: [&str; 28] = [
    "version",
    "name",
    "description",
    "seeds",
    "block",
    "material",
    "friction",
    "time",
    "self_weight",
    "shear",
    "boundary",
    "record",
    "skip_ahead",
    "loading_plate",
    "rupture",
    "fault",
    "absorbing",
    "stations",
    "medium",
    "events",
    "similarity",
    "accelerograms",
    "spectra",
    "set",
    "broadband",
    "report",
    "exchange",
    "cycles",
];

/// Sections a mutant may gain, whole.
const INJECTED: [&str; 14] = [
    "[loading_plate]\nstiffness_n_m = 1e19\n",
    "[loading_plate]\nmodulus_pa = 1e9\nthickness_m = 0.01\nnormal_pressure_pa = 1e5\n",
    "[rupture]\n",
    "[rupture]\nfracture_energy_j_m2 = 1e-300\nkr = 1.0000001\n",
    "[spectra]\nperiod_min_s = 2e-17\n",
    "[spectra]\n",
    "[accelerograms]\npre_event_s = 10.0\npost_event_s = 10.0\n",
    "[set]\ntarget = \"ec8\"\nt1_s = 1e9\n",
    "[set]\ntarget = \"csv\"\ntarget_csv = \"target.csv\"\nt1_s = 0.5\ncount = 2\nmax_per = 2\n",
    "[seeds.target]\nquantity = \"stress_drop_pa\"\nrelative = 0.02\nbatch = 2\n",
    "[report]\nseeds = [99999]\n",
    "[[record.control]]\nnodes = [1, 36, 1000000]\nquantities = [\"acceleration\"]\n",
    "[[boundary]]\nface = \"z_min\"\nfix = [\"z\"]\n",
    "[skip_ahead]\nenabled = true\n",
];

/// File names a `[friction.grid]` or CSV target may be given, made in the mutant's folder.
const INPUTS: [&str; 9] =
    ["grid.csv", "bad.csv", "fifo.csv", "zero.csv", "folder", "/etc/hostname", "../up.csv", "missing.csv", ""];

/// Writes the inputs a mutant may name into its folder `dir`: a valid grid for `[nx, ny, lc]`,
/// a grid with a NaN row, a FIFO, a link to /dev/zero, a folder and a CSV target.
fn write_inputs(dir: &Path, block: (i64, i64, f64)) {
    let (nx, ny, lc) = block;
    let mut grid = String::from("x_m,y_m,mu_static,mu_dynamic,slip_weakening_m\n");
    if (1..=200).contains(&nx) && (1..=200).contains(&ny) && lc.is_finite() && lc > 0.0 {
        for i in 0..=nx {
            for j in 0..=ny {
                grid += &format!("{},{},0.6,0.4,1e-5\n", i as f64 * lc, j as f64 * lc);
            }
        }
    }
    std::fs::write(dir.join("grid.csv"), &grid).unwrap();
    std::fs::write(dir.join("bad.csv"), grid.replacen("0.6,0.4", "NaN,0.4", 1) + "secret line\n").unwrap();
    let fifo = std::ffi::CString::new(dir.join("fifo.csv").to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) };
    let _ = std::os::unix::fs::symlink("/dev/zero", dir.join("zero.csv"));
    std::fs::create_dir_all(dir.join("folder")).unwrap();
    std::fs::write(dir.join("target.csv"), "period_s,psa_m_s2\n0.1,2.0\n1.0,2.0\n10.0,0.5\n").unwrap();
}

/// A leaf of a TOML document: its path (keys and array indices).
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

fn leaves(v: &toml::Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                path.push(Step::Key(k.clone()));
                out.push(path.clone());
                leaves(x, path, out);
                path.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(Step::Index(i));
                out.push(path.clone());
                leaves(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(v: &'a mut toml::Value, path: &[Step]) -> Option<&'a mut toml::Value> {
    let mut cur = v;
    for s in path {
        cur = match (s, cur) {
            (Step::Key(k), toml::Value::Table(t)) => t.get_mut(k)?,
            (Step::Index(i), toml::Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(cur)
}

fn remove(v: &mut toml::Value, path: &[Step]) {
    let Some((last, parent)) = path.split_last() else { return };
    match (last, at(v, parent)) {
        (Step::Key(k), Some(toml::Value::Table(t))) => {
            t.remove(k);
        }
        (Step::Index(i), Some(toml::Value::Array(a))) if *i < a.len() => {
            a.remove(*i);
        }
        _ => {}
    }
}

/// A replacement for a value: specials, scaled, wrong types, strange strings.
fn replacement(rng: &mut Rng, old: &toml::Value) -> toml::Value {
    use toml::Value as V;
    let floats = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        -0.0,
        0.0,
        5e-324,
        1e-300,
        1e300,
        -1e300,
        f64::MAX,
        -1.0,
        0.4999999999,
        1.0,
        2e-17,
    ];
    let ints = [0, -1, 1, i64::MAX, i64::MIN, 1 << 40, 10_000_001, 300_000_000, 9_999];
    let strings = ["", "é∑😀", "../x", "/dev/zero", "nan", "x_min", "all", "rupture", "S0", "S99"];
    let other = |rng: &mut Rng| match rng.below(6) {
        0 => V::Float(*rng.pick(&floats)),
        1 => V::Integer(*rng.pick(&ints)),
        2 => V::String(if rng.below(4) == 0 { "a".repeat(100_000) } else { rng.pick(&strings).to_string() }),
        3 => V::Boolean(rng.below(2) == 0),
        4 => V::Array(vec![V::Float(*rng.pick(&floats)); rng.below(4)]),
        _ => V::Table(toml::Table::new()),
    };
    match (rng.below(14), old) {
        // Plausible: a value changed by a little or by ten, of its own type.
        (0..=5, V::Float(x)) => V::Float(x * rng.pick(&[0.5, 0.9, 1.1, 2.0, 0.1, 10.0, -1.0])),
        (0..=5, V::Integer(i)) => V::Integer(i.saturating_add(*rng.pick(&[-1, 1, 2, 5]))),
        (0..=5, V::Boolean(b)) => V::Boolean(!b),
        (0..=5, V::String(_)) => V::String(rng.pick(&strings).to_string()),
        // Far: scaled by 10⁻²⁰ … 10²⁰, or a special value, of its own type.
        (6..=7, V::Float(x)) => V::Float(x * 10f64.powi(rng.below(41) as i32 - 20)),
        (6..=7, V::Integer(i)) => V::Integer(i.saturating_mul(*rng.pick(&[-1, 0, 2, 10, 1000, 1 << 20]))),
        (8..=10, V::Float(_)) => V::Float(*rng.pick(&floats)),
        (8..=10, V::Integer(_)) => V::Integer(*rng.pick(&ints)),
        (8..=10, V::String(_)) if rng.below(4) == 0 => V::String("a".repeat(100_000)),
        (11, V::Array(a)) if !a.is_empty() => V::Array(std::iter::repeat_n(a[0].clone(), 1 + rng.below(300)).collect()),
        // Another type altogether.
        _ => other(rng),
    }
}

/// The most modules a mutant's block may have: larger lattices are valid but take gigabytes and
/// seconds to minutes to build and check, which is the subject of the large-lattice limits (the
/// memory and run-length refusals), not of this fuzzing; shipped pipelines above it are coarsened.
const MAX_MODULES: f64 = 50_000.0;

/// Modules of the block a pipeline text describes (0 when it does not parse or is refused).
fn modules(text: &str) -> f64 {
    let Ok(doc) = toml::from_str::<toml::Table>(text) else { return 0.0 };
    let b = doc.get("block").and_then(|b| b.as_table());
    let get = |k: &str, d: i64| b.and_then(|b| b.get(k)).and_then(|v| v.as_integer()).unwrap_or(d);
    let n = [get("nx", 10), get("ny", 1), get("nz", 5)];
    // A count outside 1 … 10⁶ is refused whatever the others: keep it.
    if n.iter().any(|n| !(1..=1_000_000).contains(n)) { 0.0 } else { n.iter().map(|&n| n as f64).product() }
}

/// A mutant of `text` whose block has at most [`MAX_MODULES`] modules.
fn mutate(rng: &mut Rng, text: &str) -> String {
    loop {
        let m = mutate_once(rng, text);
        if modules(&m) <= MAX_MODULES {
            return m;
        }
    }
}

/// A mutant of `text`: one or two mutations, structured (on the parsed document) or textual.
fn mutate_once(rng: &mut Rng, text: &str) -> String {
    let mut doc: toml::Value = toml::from_str(text).expect("shipped pipelines parse");
    let mut textual: Vec<String> = Vec::new();
    for _ in 0..1 + rng.below(2) {
        let mut paths = Vec::new();
        leaves(&doc, &mut Vec::new(), &mut paths);
        match rng.below(16) {
            0..=8 if !paths.is_empty() => {
                let p = rng.pick(&paths).clone();
                if let Some(v) = at(&mut doc, &p) {
                    *v = replacement(rng, &v.clone());
                }
            }
            9 if !paths.is_empty() => {
                let p = rng.pick(&paths).clone();
                remove(&mut doc, &p);
            }
            10..=11 => {
                let section = *rng.pick(&INJECTED);
                textual.push(section.to_string());
            }
            12 => {
                let file = *rng.pick(&INPUTS);
                let which = if rng.below(2) == 0 {
                    format!("[friction.grid]\nfile = {file:?}\n")
                } else {
                    format!("[set]\ntarget = \"csv\"\ntarget_csv = {file:?}\n")
                };
                textual.push(which);
            }
            13 => textual.push(format!("{} = 1\n", rng.pick(&["unknown", "velocity", "young_pa", "version"]))),
            14 => textual.push(
                rng.pick(&["[block]\nnx = 1e400\n", "[material]\npoisson = 1e400\n", "x = \"\\u0000\"\n"]).to_string(),
            ),
            _ => {
                let line = rng.pick(&text.lines().collect::<Vec<_>>()).to_string();
                textual.push(line + "\n");
            }
        }
    }
    let mut out = toml::to_string(&doc).unwrap_or_default();
    // Injected text goes where TOML reads it: top-level keys first, sections at the end.
    for t in textual {
        if t.starts_with('[') {
            out.push('\n');
            out += &t;
        } else {
            out = t + &out;
        }
    }
    if rng.below(40) == 0 {
        // Cut at a byte, moved back to the start of its character (unicode values are drawn).
        let mut cut = rng.below(out.len() + 1);
        while !out.is_char_boundary(cut) {
            cut -= 1;
        }
        out.truncate(cut);
    }
    out
}

/// How one process ended.
#[derive(Debug, PartialEq)]
enum End {
    Exit(i32),
    Signal,
    /// Outlived its bound plus the grace an interrupt gets.
    Hung,
}

/// Runs `cmd` for at most `bound`, then interrupts it (SIGINT, as Ctrl-C) and gives it `grace`
/// to stop before killing it: (how it ended, stdout, stderr, whether it was interrupted).
fn bounded(mut cmd: Command, bound: Duration, grace: Duration) -> (End, String, String, bool) {
    let mut child = cmd.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("spawn stickslip");
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let t_out = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = out.read_to_end(&mut s);
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = err.read_to_end(&mut s);
        s
    });
    let start = Instant::now();
    let mut interrupted = false;
    let end = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st.code().map_or(End::Signal, End::Exit);
        }
        let t = start.elapsed();
        if !interrupted && t > bound {
            // SAFETY: signalling our own child by its pid.
            unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
            interrupted = true;
        }
        if t > bound + grace {
            let _ = child.kill();
            let _ = child.wait();
            break End::Hung;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let text = |v: Vec<u8>| String::from_utf8_lossy(&v).into_owned();
    (end, text(t_out.join().unwrap()), text(t_err.join().unwrap()), interrupted)
}

/// Whether a refusal names its field: a `field = value is not allowed` line under a top-level
/// key, the line and column of a TOML error, or the pipeline keys behind a solver's message.
fn names_a_field(err: &str) -> bool {
    let field_line = err.lines().any(|l| {
        let l = l.trim_start().trim_start_matches("- ");
        l.split_once(" = ").is_some_and(|(field, _)| {
            let top = field.split(['.', '[', ' ']).next().unwrap_or("");
            TOP_KEYS.contains(&top) && !field.contains(' ')
        })
    });
    field_line || err.contains("TOML parse error at line") || err.contains("(pipeline keys: ")
}

/// What a refusal names first: the top-level key of its first field, "toml" for a syntax error.
fn first_named(err: &str) -> String {
    if err.contains("TOML parse error") {
        return "toml".into();
    }
    err.lines()
        .filter_map(|l| l.trim_start().strip_prefix("- "))
        .filter_map(|l| l.split_once(" = "))
        .map(|(f, _)| f.split(['.', '[']).next().unwrap_or(f).to_string())
        .next()
        .unwrap_or_else(|| "other".into())
}

/// Whether `text` holds a run of 25 digits or more (a number printed without an exponent) that
/// is not in `input` (a line of the pipeline file shown as written is not the product's doing).
fn long_number(text: &str, input: &str) -> bool {
    let mut run = String::new();
    for c in text.chars().chain(std::iter::once(' ')) {
        if c.is_ascii_digit() {
            run.push(c);
            continue;
        }
        if run.len() >= 25 && !input.contains(&run) {
            return true;
        }
        run.clear();
    }
    false
}

/// Float cells of every table under `dir` that are NaN or infinite: (file, column, count).
fn non_finite(dir: &Path) -> Vec<(PathBuf, String, usize)> {
    let mut out = Vec::new();
    for f in parquet_files(dir) {
        let df = read_table(&dir.join(&f));
        for c in df.columns() {
            // Single-precision columns (series channels, Fourier amplitudes) are checked as f64.
            let c = if c.dtype() == &stickslip_support::polars::prelude::DataType::Float32 {
                c.cast(&stickslip_support::polars::prelude::DataType::Float64).unwrap()
            } else {
                c.clone()
            };
            let Ok(v) = c.as_materialized_series().f64() else { continue };
            let bad = v.iter().flatten().filter(|x| !x.is_finite()).count();
            if bad > 0 {
                out.push((f.clone(), c.name().to_string(), bad));
            }
        }
    }
    out
}

/// What a fuzz run found.
#[derive(Debug, Default)]
struct Tally {
    mutants: usize,
    refused: usize,
    accepted: usize,
    runs: usize,
    runs_finished: usize,
    runs_failed: usize,
    runs_bounded: usize,
    panics: Vec<String>,
    hangs: Vec<String>,
    unnamed: Vec<String>,
    long_numbers: Vec<String>,
    non_finite: Vec<String>,
    check_s: f64,
    run_s: f64,
    /// Refusals by what they name first: a field's top-level key, or "toml" for the syntax.
    refused_by: std::collections::BTreeMap<String, usize>,
}

impl Tally {
    fn defects(&self) -> usize {
        self.panics.len() + self.hangs.len() + self.unnamed.len() + self.long_numbers.len() + self.non_finite.len()
    }

    fn summary(&self) -> String {
        format!(
            "mutants {}: refused {}, accepted {}; bounded runs {} (finished {}, failed with a message {}, \
             stopped at the bound {}); panics {}, hangs {}, refusals without a field {}, 25-digit numbers {}, \
             non-finite values in tables {}; check {:.0} s, runs {:.0} s of process time",
            self.mutants,
            self.refused,
            self.accepted,
            self.runs,
            self.runs_finished,
            self.runs_failed,
            self.runs_bounded,
            self.panics.len(),
            self.hangs.len(),
            self.unnamed.len(),
            self.long_numbers.len(),
            self.non_finite.len(),
            self.check_s,
            self.run_s
        )
    }

    fn examples(&self) -> String {
        let mut s = String::new();
        for (what, v) in [
            ("panic", &self.panics),
            ("hang", &self.hangs),
            ("no field", &self.unnamed),
            ("long number", &self.long_numbers),
            ("non-finite", &self.non_finite),
        ] {
            for e in v.iter().take(3) {
                s += &format!("\n--- {what}: {e}");
            }
        }
        s
    }
}

/// The shipped pipelines, by name, with their text and block (nx, ny, lc). A pipeline whose block
/// has more than [`MAX_MODULES`] modules is fuzzed coarsened: Lc × k and nx, ny, nz ÷ k (the same
/// extent, so its patches and stations stay where they are), k the smallest whole factor that
/// divides them all and brings the block under the limit (or, when none divides them all, the
/// smallest that does with the sides rounded up); the name says so (`tpv5/2`).
fn shipped() -> Vec<(String, String, (i64, i64, f64))> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(repo_path("pipelines")).unwrap().flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "toml") {
            let mut text = std::fs::read_to_string(&p).unwrap();
            let mut name = p.file_stem().unwrap().to_string_lossy().into_owned();
            let mut doc: toml::Table = toml::from_str(&text).unwrap();
            let b = doc.get("block").and_then(|b| b.as_table()).cloned().unwrap_or_default();
            let get_i = |k: &str, d: i64| b.get(k).and_then(|v| v.as_integer()).unwrap_or(d);
            let (mut n, mut lc) = (
                [get_i("nx", 10), get_i("ny", 1), get_i("nz", 5)],
                b.get("lc_m").and_then(|v| v.as_float()).unwrap_or(0.1),
            );
            // A [cycles] pipeline never builds its block (its fault's stiffness is computed by
            // cosines): fuzzed at size.
            if modules(&text) > MAX_MODULES && !doc.contains_key("cycles") {
                // A block whose sides share no such factor (TPV101's 560 × 205 × 200) is rounded up
                // to whole coarse modules: its extent grows by less than one of them.
                let fits = |k: i64| n.iter().map(|&x| ((x + k - 1) / k) as f64).product::<f64>() <= MAX_MODULES;
                let k = (2..=64)
                    .find(|&k| n.iter().all(|&x| x % k == 0) && fits(k))
                    .or_else(|| (2..=64).find(|&k| fits(k)))
                    .unwrap_or_else(|| panic!("{name}: no whole factor brings its block under {MAX_MODULES} modules"));
                n = n.map(|x| (x + k - 1) / k);
                lc *= k as f64;
                let block = doc.entry("block").or_insert(toml::Value::Table(toml::Table::new()));
                let block = block.as_table_mut().unwrap();
                for (key, v) in ["nx", "ny", "nz"].iter().zip(n) {
                    block.insert(key.to_string(), toml::Value::Integer(v));
                }
                block.insert("lc_m".into(), toml::Value::Float(lc));
                text = toml::to_string(&doc).unwrap();
                name = format!("{name}/{k}");
            }
            out.push((name, text, (n[0], n[1], lc)));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Runs `work` on every item of `items` on `threads` workers.
fn parallel<T: Send>(items: Vec<T>, threads: usize, work: impl Fn(T) + Sync) {
    let queue = Mutex::new(items.into_iter());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                loop {
                    let Some(item) = queue.lock().unwrap().next() else { break };
                    work(item);
                }
            });
        }
    });
}

/// One mutant: its index, label (`pipeline#k`), text and the block its inputs are made for.
struct Mutant {
    index: usize,
    label: String,
    text: String,
    block: (i64, i64, f64),
}

impl Mutant {
    /// Its folder under `root`, with its pipeline and the inputs it may name.
    fn folder(&self, root: &Path) -> PathBuf {
        let dir = root.join(format!("m{}", self.index));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        write_inputs(&dir, self.block);
        std::fs::write(dir.join("p.toml"), &self.text).unwrap();
        dir
    }

    fn what(&self, msg: &str) -> String {
        format!("{}: {msg}\n{:.2000}", self.label, self.text)
    }
}

/// Fuzzes `per_pipeline` mutants of each shipped pipeline (seed `seed`) through `check`, then
/// runs `runs` of the accepted ones, evenly spaced among them, for at most `run_bound` each;
/// `threads` workers. Which mutants are drawn and run depends only on the seed.
fn fuzz(per_pipeline: usize, runs: usize, seed: u64, run_bound: Duration, threads: usize) -> Tally {
    let root = scratch_dir(&format!("fuzz-{seed}"));
    let pipelines = shipped();
    let mut mutants = Vec::new();
    let mut rng = Rng(seed);
    for k in 0..per_pipeline {
        for (name, text, block) in &pipelines {
            let text = mutate(&mut rng, text);
            mutants.push(Mutant { index: mutants.len(), label: format!("{name}#{k}"), text, block: *block });
        }
    }
    let tally = Mutex::new(Tally::default());
    let accepted = Mutex::new(Vec::new());
    parallel(mutants.iter().collect(), threads, |m: &Mutant| {
        let dir = m.folder(&root);
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_stickslip"));
        cmd.args(["check", "p.toml", "--seeds", "2"]).current_dir(&dir);
        let t0 = Instant::now();
        let (end, out, err, _) = bounded(cmd, Duration::from_secs(60), Duration::from_secs(10));
        let mut t = tally.lock().unwrap();
        t.mutants += 1;
        t.check_s += t0.elapsed().as_secs_f64();
        if long_number(&out, &m.text) || long_number(&err, &m.text) {
            t.long_numbers.push(m.what(&format!("{out:.2000}{err:.2000}")));
        }
        match end {
            End::Exit(0) => {
                t.accepted += 1;
                accepted.lock().unwrap().push(m.index);
            }
            End::Exit(1) => {
                t.refused += 1;
                if !names_a_field(&err) {
                    t.unnamed.push(m.what(&format!("check: {err:.2000}")));
                }
                *t.refused_by.entry(first_named(&err)).or_default() += 1;
            }
            End::Hung => t.hangs.push(m.what("check did not end")),
            other => t.panics.push(m.what(&format!("check {other:?}: {err:.3000}"))),
        }
        drop(t);
        let _ = std::fs::remove_dir_all(&dir);
    });
    let mut accepted = accepted.into_inner().unwrap();
    accepted.sort();
    let chosen: Vec<&Mutant> = if accepted.len() <= runs {
        accepted.iter().map(|&i| &mutants[i]).collect()
    } else {
        (0..runs).map(|j| &mutants[accepted[j * accepted.len() / runs]]).collect()
    };
    parallel(chosen, threads, |m: &Mutant| {
        let dir = m.folder(&root);
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_stickslip"));
        cmd.args(["run", "p.toml", "--seed", "7", "--out", "out", "--quiet"]).current_dir(&dir);
        let t0 = Instant::now();
        let (end, _, err, interrupted) = bounded(cmd, run_bound, Duration::from_secs(20));
        let run_s = t0.elapsed().as_secs_f64();
        let bad = if end != End::Hung { non_finite(&dir.join("out")) } else { vec![] };
        let mut t = tally.lock().unwrap();
        t.runs += 1;
        t.run_s += run_s;
        if long_number(&err, &m.text) {
            t.long_numbers.push(m.what(&format!("run: {err:.2000}")));
        }
        if !bad.is_empty() {
            t.non_finite.push(m.what(&format!("{bad:?}")));
        }
        match end {
            End::Exit(0) => t.runs_finished += 1,
            End::Exit(1) | End::Exit(130) if interrupted => t.runs_bounded += 1,
            End::Exit(1) => t.runs_failed += 1,
            End::Hung => t.hangs.push(m.what(&format!("run outlived its bound: {err:.1000}"))),
            other => t.panics.push(m.what(&format!("run {other:?}: {err:.3000}"))),
        }
        drop(t);
        let _ = std::fs::remove_dir_all(&dir);
    });
    tally.into_inner().unwrap()
}

fn threads() -> usize {
    std::thread::available_parallelism().map_or(2, |n| n.get()).min(4)
}

#[test]
fn fuzz_every_shipped_pipeline() {
    let t = fuzz(30, 24, 32, Duration::from_secs(10), threads());
    println!("{}\nrefused by: {:?}", t.summary(), t.refused_by);
    assert_eq!(t.defects(), 0, "{}{}", t.summary(), t.examples());
    assert!(t.refused > 50 && t.accepted > 30 && t.runs >= 20, "a fuzz run that tests little: {}", t.summary());
}

/// The long run of docs/guide/refusals.md: `scripts/fuzz.sh` (or `STICKSLIP_FUZZ_MUTANTS=10000
/// STICKSLIP_FUZZ_RUNS=500 cargo test --release -p stickslip --test fuzz -- --ignored
/// --nocapture`).
#[test]
#[ignore]
fn fuzz_long() {
    let env = |k: &str, d: u64| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
    let mutants = env("STICKSLIP_FUZZ_MUTANTS", 10_000) as usize;
    let runs = env("STICKSLIP_FUZZ_RUNS", 500) as usize;
    let seed = env("STICKSLIP_FUZZ_SEED", 2026);
    let per = mutants.div_ceil(shipped().len());
    let start = Instant::now();
    let t = fuzz(per, runs, seed, Duration::from_secs(30), threads());
    println!("seed {seed}, {} workers: {}; wall {:.0} s", threads(), t.summary(), start.elapsed().as_secs_f64());
    println!("refused by: {:?}", t.refused_by);
    assert_eq!(t.defects(), 0, "{}{}", t.summary(), t.examples());
}
