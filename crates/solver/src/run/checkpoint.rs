//! A run's checkpoint (docs/model.md §19): the state of its lanes and what they recorded so far,
//! written now and then (and when the run is asked to stop) so that a run stopped by a cluster's
//! preemption, its wall time or Ctrl-C resumes where it was and gives the numbers of a run that
//! was never stopped, bit for bit. One file per seed, or per rank of a split seed; each written
//! to a temporary file and renamed over the last, so a file is whole or absent.
//!
//! Everything not in the file is rebuilt from the seed as the run started (the random fields,
//! Δt and the critical step, the stiffness): the file holds the time levels, the contact and
//! loading state, the ledgers, the slip log, the damage of bars that crack, the medium's memory
//! variables, each lane's stage and its recorder (samples, traces, the fault summary being
//! built). The skip-ahead's state is not, so a run with `[skip_ahead]` is not checkpointed.

use std::io::{BufReader, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

use bincode::{Decode, Encode};

use crate::recording::Recorder;
use crate::scene::SettleMethod;
use crate::statics::CriticalStep;
use crate::step::State;

/// The format's version: a file of another is not read.
const FORMAT: u32 = 3;
/// What a checkpoint file starts with.
const MAGIC: &[u8; 16] = b"stickslip-ckpt\0\0";

/// Where and how often a run writes its checkpoint, and what it must have been written for.
#[derive(Debug)]
pub struct Checkpoint {
    /// This run's file (one per seed; one per rank of a split seed).
    pub path: PathBuf,
    /// Wall-clock seconds between two checkpoints (rank 0's clock in a split run), if any.
    pub every_s: Option<f64>,
    /// Steps between two checkpoints, if any (taken at the run's progress points, at most 512
    /// steps apart: the first such point at or after each multiple).
    pub every_steps: Option<u64>,
    /// What the file is for (e.g. the pipeline's hash): a file written for another is not resumed.
    pub key: String,
    /// The last write that failed, if any (the run goes on: a later write may succeed).
    failed: Mutex<Option<String>>,
}

impl Checkpoint {
    /// A checkpoint at `path` every `every_s` seconds of wall clock and/or `every_steps` steps,
    /// for `key`.
    pub fn new(path: PathBuf, every_s: Option<f64>, every_steps: Option<u64>, key: String) -> Checkpoint {
        Checkpoint { path, every_s, every_steps, key, failed: Mutex::new(None) }
    }

    /// Why the last write failed, if it did.
    pub fn failure(&self) -> Option<String> {
        self.failed.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The step a run would resume from, if the file holds a checkpoint for `key` (read from the
    /// file's header only).
    pub fn resumes_at(&self) -> Option<u64> {
        let file = std::fs::File::open(&self.path).ok()?;
        let length = file.metadata().ok()?.len();
        let header = read_header(&mut BufReader::new(file)).ok()?;
        (header.key == self.key && whole_length(&header).ok()? == length).then_some(header.steps)
    }

    /// Removes the file (the run it was for has finished and been written).
    pub fn remove(&self) -> std::io::Result<()> {
        match std::fs::remove_file(&self.path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(e),
            _ => Ok(()),
        }
    }

    pub(super) fn note_failure(&self, why: String) {
        *self.failed.lock().unwrap_or_else(|e| e.into_inner()) = Some(why);
    }
}

/// When the next checkpoint is due.
pub(super) struct Due {
    last_step: u64,
    last_time: Instant,
}

impl Due {
    pub(super) fn new(steps: u64) -> Due {
        Due { last_step: steps, last_time: Instant::now() }
    }

    /// Whether a checkpoint is due at step `steps`.
    pub(super) fn due(&self, c: &Checkpoint, steps: u64) -> bool {
        let by_steps = c.every_steps.is_some_and(|n| steps / n.max(1) > self.last_step / n.max(1));
        let by_time = c.every_s.is_some_and(|s| self.last_time.elapsed().as_secs_f64() >= s);
        by_steps || by_time
    }

    pub(super) fn taken(&mut self, steps: u64) {
        *self = Due::new(steps);
    }
}

/// What identifies the run a file was written by; checked before its state is read.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub(super) struct Header {
    pub key: String,
    pub seeds: Vec<u64>,
    pub nodes: u64,
    pub bars: u64,
    /// Each lane's Δt, as bits.
    pub dt: Vec<u64>,
    pub rank: u64,
    pub ranks: u64,
    /// Committed steps.
    pub steps: u64,
    /// Bytes of the body that follows.
    pub body: u64,
}

impl Header {
    /// The header of a run of `model` with `seeds` and their steps `dts` on `rank` of `ranks`,
    /// at `steps` (the body's length is filled in as it is written).
    pub(super) fn of(
        key: &str,
        seeds: &[u64],
        model: &crate::Model,
        dts: &[f64],
        (rank, ranks): (usize, usize),
        steps: u64,
    ) -> Header {
        Header {
            key: key.to_string(),
            seeds: seeds.to_vec(),
            nodes: model.node_count() as u64,
            bars: model.bar_count() as u64,
            dt: dts.iter().map(|d| d.to_bits()).collect(),
            rank: rank as u64,
            ranks: ranks as u64,
            steps,
            body: 0,
        }
    }
}

/// Where a lane was.
#[derive(Debug, Clone, Copy, Encode, Decode)]
pub(super) enum StageAt {
    Settling { max_steps: u64 },
    Shearing { origin: u64, steps: u64, stride: u64 },
    Done { origin: u64, stride: u64, steps: u64 },
}

/// One lane, as written.
#[derive(Encode, Decode)]
pub(super) struct LaneAt {
    pub stage: StageAt,
    pub critical: Option<CriticalStep>,
    pub recorder: Option<Recorder>,
    pub settle_steps: u64,
    pub settled_by: SettleMethod,
    pub settle_note: Option<String>,
}

/// The state and the lanes.
#[derive(Encode, Decode)]
pub(super) struct Body<const L: usize> {
    pub state: State<L>,
    pub lanes: Vec<LaneAt>,
}

/// A lane being written: [`LaneAt`]'s layout, borrowing what is large.
#[derive(Encode)]
pub(super) struct LaneRef<'a> {
    pub stage: StageAt,
    pub critical: Option<CriticalStep>,
    pub recorder: Option<&'a Recorder>,
    pub settle_steps: u64,
    pub settled_by: SettleMethod,
    pub settle_note: &'a Option<String>,
}

/// [`Body`] being written.
#[derive(Encode)]
pub(super) struct BodyRef<'a, const L: usize> {
    pub state: &'a State<L>,
    pub lanes: &'a [LaneRef<'a>],
}

fn config() -> impl bincode::config::Config {
    bincode::config::standard().with_fixed_int_encoding().with_little_endian()
}

/// Writes `body` under `header` to `path`, through a temporary file renamed over it.
pub(super) fn write<const L: usize>(path: &Path, header: Header, body: &BodyRef<'_, L>) -> Result<(), String> {
    let tmp = path.with_extension("ckpt.tmp");
    let written = write_to(path, &tmp, header, body);
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

fn write_to<const L: usize>(path: &Path, tmp: &Path, mut header: Header, body: &BodyRef<'_, L>) -> Result<(), String> {
    let fail = |what: &str, e: &dyn std::fmt::Display| format!("{what} {}: {e}", tmp.display());
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| fail("creating the folder of", &e))?;
    }
    let file = std::fs::File::create(tmp).map_err(|e| fail("creating", &e))?;
    let mut out = BufWriter::with_capacity(1 << 22, file);
    header.body = 0;
    let head = bincode::encode_to_vec(&header, config()).map_err(|e| fail("encoding", &e))?;
    out.write_all(MAGIC).map_err(|e| fail("writing", &e))?;
    out.write_all(&FORMAT.to_le_bytes()).map_err(|e| fail("writing", &e))?;
    out.write_all(&head).map_err(|e| fail("writing", &e))?;
    let mut counted = Counted { inner: out, bytes: 0 };
    bincode::encode_into_std_write(body, &mut counted, config()).map_err(|e| fail("writing", &e))?;
    let mut file = counted.inner.into_inner().map_err(|e| fail("writing", &e.error()))?;
    // The body's length is the header's last field (fixed-width integers): written in place.
    let at = (MAGIC.len() + 4 + head.len() - 8) as u64;
    file.seek(SeekFrom::Start(at)).map_err(|e| fail("writing", &e))?;
    file.write_all(&counted.bytes.to_le_bytes()).map_err(|e| fail("writing", &e))?;
    file.sync_all().map_err(|e| fail("syncing", &e))?;
    drop(file);
    std::fs::rename(tmp, path).map_err(|e| format!("renaming {} to {}: {e}", tmp.display(), path.display()))
}

/// The header of a checkpoint file.
fn read_header(file: &mut impl Read) -> Result<Header, String> {
    let mut magic = [0u8; 16];
    let mut format = [0u8; 4];
    file.read_exact(&mut magic).map_err(|e| e.to_string())?;
    file.read_exact(&mut format).map_err(|e| e.to_string())?;
    if &magic != MAGIC {
        return Err("not a stickslip checkpoint".into());
    }
    if u32::from_le_bytes(format) != FORMAT {
        return Err(format!("format {} (this stickslip reads {FORMAT})", u32::from_le_bytes(format)));
    }
    bincode::decode_from_std_read(file, config()).map_err(|e| e.to_string())
}

/// Reads `path` if it holds the checkpoint of the run `expected` describes (any number of steps):
/// `Ok(None)` when there is no file, an error when there is one that is not for this run or not
/// whole.
pub(super) fn read<const L: usize>(path: &Path, expected: &Header) -> Result<Option<(u64, Body<L>)>, String> {
    let file = match std::fs::File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e.to_string()),
    };
    let length = file.metadata().map_err(|e| e.to_string())?.len();
    let mut file = BufReader::with_capacity(1 << 22, file);
    let header = read_header(&mut file)?;
    let same = Header { steps: header.steps, body: header.body, ..expected.clone() };
    if header != same {
        return Err(format!(
            "it was written for another run (seeds {:?}, rank {} of {}, {} nodes)",
            header.seeds, header.rank, header.ranks, header.nodes
        ));
    }
    let whole = whole_length(&header)?;
    if whole != length {
        return Err(format!("it is {length} bytes long, not the {whole} its header says"));
    }
    let body: Body<L> = bincode::decode_from_std_read(&mut file, config()).map_err(|e| e.to_string())?;
    if body.lanes.len() != L || body.state.u.np1.len() as u64 != header.nodes {
        return Err("its state is not this run's size".into());
    }
    Ok(Some((header.steps, body)))
}

/// The length of the file `header` heads.
fn whole_length(header: &Header) -> Result<u64, String> {
    let head = bincode::encode_to_vec(header, config()).map_err(|e| e.to_string())?.len() as u64;
    Ok(MAGIC.len() as u64 + 4 + head + header.body)
}

/// A writer that counts what passes through it.
struct Counted<W> {
    inner: W,
    bytes: u64,
}

impl<W: Write> Write for Counted<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.bytes += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}
