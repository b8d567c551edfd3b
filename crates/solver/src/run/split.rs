//! One seed of a scene split over ranks (docs/model.md §19): the run loop of one process
//! ([`run_lanes`](crate::run::run_lanes)), with the halo exchanged after every step, the critical
//! step found by every rank together, the self-weight stage's equilibrium check summed in the one
//! process's order (handed from rank to rank), the blow-up check and the decision to stop agreed
//! by every rank, and rank 0 recording, each step, the stations and drivers other ranks hold.
//! Rank 0's [`RunOutput`] is then the one process's, bit for bit.
//!
//! The energy ledger is summed layer by layer on one process too ([`Model::energy_layers`]): each
//! rank sends rank 0 its layers' terms of every step, and its layers' kinetic and elastic energy
//! when a sample records them, and rank 0 adds the layers bottom up.
//!
//! Not yet: the static self-weight (conjugate gradients), the skip-ahead, and drivers or a loading
//! plate held by more than one rank; each is refused before the run starts.

use std::ops::ControlFlow;

use super::lanes::{Hooks, Remote, run_lanes_with};
use super::{Checkpoint, RunOptions, RunOutput, time_step};
use crate::NodeId;
use crate::error::SolverError;
use crate::layout::Bars;
use crate::ledger::{Energy, fold_layers, total};
use crate::model::{Model, canonical_of_internal};
use crate::observe::Observed;
use crate::scene::ControlChannel;
use crate::split::{Halo, Neighbours, Partition, Window, handed_sum};
use crate::statics::CriticalStep;
use crate::statics::critical::critical_step_split;
use crate::step::energy::{kinetic_energy_layers, strain_energy_layers};
use crate::step::{LaneSetup, LaneView, Params, State};

/// What one rank of a split scene holds: its part of the model and where the cuts are.
#[derive(Clone, Copy)]
pub struct RankPart<'a> {
    /// [`Model::window`] of `partition.window(rank)`.
    pub model: &'a Model,
    /// The cuts.
    pub partition: &'a Partition,
}

/// Runs `seed` on this rank's `part` of the scene. Every rank calls it with the same seed and
/// options; rank 0 gets the run's output, the others `None` (or their own error, when the run
/// stopped with one: every rank stops with rank 0). The seed's critical step is found by every
/// rank together ([`critical_step_split`]). `progress` is rank 0's: when it asks to stop, every
/// rank stops. With a `checkpoint` (this rank's file), the run resumes from it when every rank's
/// holds the same step, and every rank writes its own together.
pub fn run_split(
    part: RankPart<'_>,
    seed: u64,
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
    ranks: &mut dyn Neighbours,
    checkpoint: Option<&Checkpoint>,
) -> Option<Result<RunOutput, SolverError>> {
    let RankPart { model, partition } = part;
    let rank = ranks.rank();
    let window = partition.window(rank);
    assert_eq!(model.split_window(), Some(&window), "rank {rank}'s model is its window of the partition");
    if let Err(why) = splittable(model.scene()) {
        return (rank == 0).then_some(Err(SolverError::Unsupported(why)));
    }
    // Which rank holds the drivers (or the plate): at most one.
    let mine = [f64::from(u8::from(!model.drivers().is_empty() || !model.plate().is_empty()))];
    let mut holders = [0.0];
    let all = ranks.gather(&mine);
    if rank == 0 {
        let with: Vec<usize> = all.iter().enumerate().filter(|(_, v)| v[0] > 0.0).map(|(r, _)| r).collect();
        holders[0] = match with.as_slice() {
            [] => -1.0,
            [r] => *r as f64,
            _ => -2.0,
        };
    }
    ranks.broadcast(&mut holders);
    if holders[0] == -2.0 {
        let why =
            "drivers or a loading plate held by more than one rank of a split scene are not supported yet".to_string();
        return (rank == 0).then_some(Err(SolverError::Unsupported(why)));
    }
    let driver_rank = (holders[0] >= 0.0).then_some(holders[0] as usize);
    // The control channels rank 0 does not hold, and who sends each.
    let dims = model.scene().dims;
    let root = partition.window(0);
    let owner =
        |id: NodeId| (0..partition.ranks()).find(|&r| partition.window(r).owns(internal(dims, id))).expect("an owner");
    let remote: Vec<(ControlChannel, usize)> = model
        .scene()
        .record
        .control
        .iter()
        .filter(|c| root.local(internal(dims, c.node)).is_none())
        .map(|&c| (c, owner(c.node)))
        .collect();
    let sent: Vec<(ControlChannel, usize)> = remote
        .iter()
        .filter(|(_, r)| *r == rank)
        .map(|&(c, _)| (c, model.held(c.node).expect("an owned node is held")))
        .collect();
    let mut hooks = Split {
        window,
        ranks,
        halo: Halo::default(),
        remote,
        sent,
        driver_rank: driver_rank.filter(|&r| r != 0),
        values: Remote::default(),
    };
    let [out] = run_lanes_with::<1, _>(model, [seed], options, progress, &mut hooks, checkpoint);
    (rank == 0 || out.is_err()).then_some(out)
}

/// Why `scene`'s runs cannot be split over `ranks` ranks, if they cannot: a block too thin for
/// them, bars that crack, or what the split run does not do yet (module doc).
pub fn split_refusal(scene: &crate::Scene, ranks: usize) -> Option<String> {
    if let Err(e) = Partition::new(scene.dims, ranks) {
        return Some(format!("{e} (block.nz = {})", scene.dims.nz));
    }
    if scene.rupture.is_some() {
        return Some("a scene whose bars crack ([rupture]) lists its bars and is not split".into());
    }
    splittable(scene).err()
}

/// Why a scene's run cannot be split yet, if it cannot.
fn splittable(scene: &crate::Scene) -> Result<(), String> {
    if scene.self_weight.gravity_m_s2 != 0.0 && scene.self_weight.method == crate::scene::SettleMethod::Static {
        return Err(
            "the static self-weight (conjugate gradients over the whole block) of a split scene is not built yet: set \
             self_weight.method = \"dynamic\""
                .into(),
        );
    }
    if scene.skip_ahead.enabled {
        return Err(
            "the quasi-static skip-ahead of a split scene is not built yet: set skip_ahead.enabled = false".into()
        );
    }
    Ok(())
}

fn internal(dims: crate::Dims, id: NodeId) -> usize {
    crate::model::internal_of_canonical(dims, id)
}

/// The hooks of one rank.
struct Split<'a> {
    window: Window,
    ranks: &'a mut dyn Neighbours,
    halo: Halo,
    /// Every control channel rank 0 does not hold, with the rank that sends it.
    remote: Vec<(ControlChannel, usize)>,
    /// The channels this rank sends, with their window index.
    sent: Vec<(ControlChannel, usize)>,
    /// The rank other than 0 that holds the drivers, if one does.
    driver_rank: Option<usize>,
    /// On rank 0, what the others sent this step.
    values: Remote,
}

impl Hooks<1> for Split<'_> {
    fn prepare(
        &mut self,
        model: &Model,
        seed: u64,
        options: RunOptions,
    ) -> Result<(LaneSetup, CriticalStep), SolverError> {
        let setup = (|| {
            Ok::<_, SolverError>(LaneSetup {
                dt_s: 0.0,
                stiffness: model.lane_stiffness_on(seed, options.parallel_step)?,
                friction: model.friction_factors(seed)?,
                strength: None,
                fault: model.fault_loads(seed)?,
            })
        })();
        // Every rank goes on, or none: a rank that could not set its part up says so.
        let failed = self.ranks.gather(&[f64::from(u8::from(setup.is_err()))]);
        let mut first = [-1.0];
        if let Some(r) = failed.iter().position(|v| v[0] != 0.0) {
            first[0] = r as f64;
        }
        self.ranks.broadcast(&mut first);
        let setup = match setup {
            Err(e) => return Err(e),
            Ok(_) if first[0] >= 0.0 => {
                return Err(SolverError::Unsupported(format!(
                    "rank {} of the split run could not set its part of seed {seed} up",
                    first[0] as usize
                )));
            }
            Ok(setup) => setup,
        };
        // The same numbers on every rank: any error is every rank's.
        let critical = if let Bars::Listed(_) = model.layout() {
            // A block whose bars are listed is small (below STENCIL_MIN_BARS): every rank finds the
            // whole block's critical step as one process does.
            let whole = Model::new(model.scene().clone());
            let k = whole.lane_stiffness_on(seed, options.parallel_step)?;
            crate::statics::critical_step_on(&whole, &k, options.parallel_step)?
        } else {
            critical_step_split(model, &setup.stiffness, options.parallel_step, self.ranks)?
        };
        let dt_s = time_step(model, seed, &critical, options)?;
        Ok((LaneSetup { dt_s, ..setup }, critical))
    }

    fn after_step(&mut self, params: &Params<'_, 1>, state: &mut State<1>) {
        self.halo.exchange(&self.window, &mut state.u.np1, self.ranks);
        let ledger = params.model.scene().record.energy;
        if self.remote.is_empty() && self.driver_rank.is_none() && !ledger {
            return;
        }
        let view = LaneView { params, state, lane: 0 };
        let mut mine: Vec<f64> =
            self.sent.iter().map(|&(c, node)| view.kinematic(node, c.quantity)[c.component.axis()]).collect();
        if self.driver_rank == Some(self.ranks.rank()) {
            mine.push(view.driver_force());
        }
        // The step's work terms of each layer this rank owns, after what it sends for stations.
        mine.extend(state.energy_parts.iter().flat_map(|p| p[0].work_terms()));
        let all = self.ranks.gather(&mine);
        if self.ranks.rank() == 0 {
            let mut next = vec![0usize; all.len()];
            self.values.control.clear();
            for &(c, r) in &self.remote {
                self.values.control.push((c, all[r][next[r]]));
                next[r] += 1;
            }
            if let Some(r) = self.driver_rank {
                self.values.driver_force = Some(all[r][next[r]]);
                next[r] += 1;
            }
            if ledger {
                // Every layer's terms, bottom up: the one process's sum.
                let parts: Vec<Energy> = all
                    .iter()
                    .zip(&next)
                    .flat_map(|(v, &from)| v[from..].chunks_exact(9).map(Energy::from_work_terms))
                    .collect();
                state.energy[0].add_work(&fold_layers(parts.iter()));
            }
        }
    }

    fn state_energy(&mut self, view: &LaneView<'_, '_, 1>) {
        let (model, u) = (view.params.model, &view.state.u);
        let kinetic = kinetic_energy_layers(model, &u.np1, &u.n, 0);
        let elastic = strain_energy_layers(model, view.params.stiffness(), &u.n, &u.np1, 0);
        let mut mine = kinetic;
        mine.extend(elastic);
        let all = self.ranks.gather(&mine);
        if self.ranks.rank() == 0 {
            // Each rank's layers: its kinetic sums, then its elastic ones.
            let (mut kinetic, mut elastic) = (Vec::new(), Vec::new());
            for v in &all {
                let (k, e) = v.split_at(v.len() / 2);
                kinetic.extend_from_slice(k);
                elastic.extend_from_slice(e);
            }
            let dt = view.params.dt(0);
            self.values.energy = Some((0.5 * total(&kinetic) / (dt * dt), 0.5 * total(&elastic)));
        }
    }

    fn blowup(&mut self, view: &LaneView<'_, '_, 1>, parallel: bool) -> Option<(NodeId, String)> {
        // Each rank's first bad owned node per component, as (global internal index, new, old).
        let u = &view.state.u;
        let mut mine = Vec::with_capacity(9);
        for c in 0..3 {
            match view.first_blowup(c, self.window.owned.clone(), parallel) {
                Some(i) => mine.extend([self.window.global(i) as f64, u.np1.c[c][i][0], u.n.c[c][i][0]]),
                None => mine.extend([-1.0, 0.0, 0.0]),
            }
        }
        let all = self.ranks.gather(&mine);
        // The one process's: the first component with a bad node, its first node.
        let mut found = [-1.0, 0.0, 0.0, 0.0];
        if self.ranks.rank() == 0 {
            'components: for c in 0..3 {
                for v in &all {
                    if v[3 * c] >= 0.0 {
                        found = [v[3 * c], c as f64, v[3 * c + 1], v[3 * c + 2]];
                        break 'components;
                    }
                }
            }
        }
        self.ranks.broadcast(&mut found);
        if found[0] < 0.0 {
            return None;
        }
        let id = canonical_of_internal(view.params.model.scene().dims, found[0] as usize);
        Some((id, view.blowup_what(found[1] as usize, found[2], found[3])))
    }

    fn out_of_balance(&mut self, view: &LaneView<'_, '_, 1>) -> f64 {
        let mut terms = Vec::with_capacity(3 * self.window.owned.len());
        view.out_of_balance_terms(self.window.owned.clone(), |t| terms.push(t));
        handed_sum(self.ranks, 0.0, &terms, 3).sqrt()
    }

    fn weight_norm(&mut self, model: &Model, gravity: f64) -> f64 {
        let mass = &model.mass()[self.window.owned.clone()];
        let terms: Vec<f64> = mass.iter().map(|m| m * m).collect();
        handed_sum(self.ranks, std::iter::empty::<f64>().sum(), &terms, 1).sqrt() * gravity
    }

    fn place(&self) -> (usize, usize) {
        (self.ranks.rank(), self.ranks.size())
    }

    fn agree(&mut self, stop: bool, save: bool) -> (bool, bool) {
        let mut flags = [f64::from(u8::from(stop)), f64::from(u8::from(save))];
        self.ranks.broadcast(&mut flags);
        (flags[0] != 0.0, flags[1] != 0.0)
    }

    fn resume(&mut self, at: Option<u64>) -> bool {
        let all = self.ranks.gather(&[at.map_or(-1.0, |s| s as f64)]);
        let mut same = [0.0];
        if self.ranks.rank() == 0 {
            same[0] = f64::from(u8::from(all[0][0] >= 0.0 && all.iter().all(|v| v[0] == all[0][0])));
        }
        self.ranks.broadcast(&mut same);
        same[0] != 0.0
    }

    fn records(&self) -> bool {
        self.ranks.rank() == 0
    }

    fn remote(&self) -> Option<&Remote> {
        (self.ranks.rank() == 0).then_some(&self.values)
    }
}
