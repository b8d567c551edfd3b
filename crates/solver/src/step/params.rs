//! The parameters of `L` seeds advancing together: the model, each seed's bar stiffness and
//! friction coefficients, and the per-lane time step, damping and body force.

use crate::fault::{FaultLanes, FaultLoads};
use crate::field::Lanes;
use crate::laws::FrictionLaws;
use crate::model::Model;
use crate::step::anelastic::AnelasticParams;
use crate::step::integrate::Coefficients;
use crate::step::rupture::RuptureParams;
use crate::stiffness::{LaneStiffness, Stiffness, StiffnessRef};

/// Per-lane set-up of a batch.
#[derive(Clone, Debug)]
pub struct LaneSetup {
    /// Time step (s).
    pub dt_s: f64,
    /// Bar stiffness (internal order), e.g. [`Model::lane_stiffness`].
    pub stiffness: LaneStiffness,
    /// Friction factor per contact node, e.g. [`Model::friction_factors`].
    pub friction: Vec<f64>,
    /// Peak elongation per bar (kernel units) when the scene's bars crack, e.g.
    /// [`Model::bar_strength`]; `None`: elastic bars. Every lane of a batch has it or none does.
    pub strength: Option<Vec<f64>>,
    /// The fault's loads on every contact node when the base is a fault (docs/model.md §15),
    /// e.g. [`Model::fault_loads`]; every lane of a batch has them or none does.
    pub fault: Option<FaultLoads>,
}

/// What the step reads and does not change.
#[derive(Clone, Debug)]
pub struct Params<'m, const L: usize> {
    /// The model.
    pub model: &'m Model,
    /// Bar stiffness per lane (see [`crate::step::bars`] and [`crate::stiffness`]).
    pub k: Stiffness<L>,
    /// The friction law's coefficients of each contact node, per lane (field factor applied).
    pub friction: FrictionLaws<L>,
    /// The bilinear law's peaks and `Kr` when bars crack (docs/model.md §11).
    pub rupture: Option<RuptureParams<L>>,
    /// Each lane's fault loads when the base is a fault (docs/model.md §15).
    pub fault: Option<FaultLanes<L>>,
    /// The medium's memory variables and dashpots (docs/model.md §18); `None`: elastic bars.
    pub anelastic: Option<AnelasticParams<L>>,
    dt: Lanes<L>,
    damping: Lanes<L>,
    body: [Lanes<L>; 3],
    coef: Coefficients<L>,
}

impl<'m, const L: usize> Params<'m, L> {
    /// Every contact node's state variable at the start of a run, lane by lane
    /// ([`crate::laws::Law::initial_state`]), from its initial shear and normal loads on a fault.
    pub fn initial_states(&self) -> Vec<[f64; L]> {
        self.friction.initial_states(|ci, l| match &self.fault {
            Some(f) => (f.shear_n[0][ci][l].hypot(f.shear_n[1][ci][l]), f.normal_n[ci][l]),
            None => (0.0, 0.0),
        })
    }

    /// Parameters of `L` seeds with no damping and no body force.
    pub fn new(model: &'m Model, lanes: &[LaneSetup; L]) -> Self {
        let nb = model.bar_count();
        let nc = model.contact().len();
        for lane in lanes {
            assert_eq!(lane.friction.len(), nc, "one friction factor per contact node");
        }
        let k = Stiffness::interleave(nb, lanes.each_ref().map(|lane| &lane.stiffness));
        assert!(
            matches!(
                (&k, model.layout()),
                (Stiffness::PerBar(_), _) | (Stiffness::Factored(_), crate::layout::Bars::Stencil(_))
            ),
            "factored stiffness is for a stencil lattice"
        );
        let friction = FrictionLaws::new(&model.scene().friction.law.background, nc, |c, l| {
            model.node_friction(c, lanes[l].friction[c])
        });
        let rupture = match (lanes.iter().all(|l| l.strength.is_some()), lanes.iter().all(|l| l.strength.is_none())) {
            (true, _) => {
                let kr = model.scene().rupture.as_ref().expect("lanes with a strength need a scene with [rupture]").kr;
                let mut peak = vec![[0.0; L]; nb];
                for (l, lane) in lanes.iter().enumerate() {
                    let s = lane.strength.as_ref().expect("checked");
                    assert_eq!(s.len(), nb, "one strength per bar");
                    for (pb, &v) in peak.iter_mut().zip(s) {
                        pb[l] = v;
                    }
                }
                Some(RuptureParams { peak, kr })
            }
            (_, true) => None,
            _ => panic!("every lane of a batch has a strength, or none does"),
        };
        let fault = match lanes.iter().map(|l| l.fault.as_ref()).collect::<Option<Vec<&FaultLoads>>>() {
            Some(loads) => {
                for f in &loads {
                    assert_eq!(f.normal_n.len(), nc, "one fault load per contact node");
                }
                Some(FaultLanes::new(loads.try_into().expect("one load per lane")))
            }
            None => {
                assert!(lanes.iter().all(|l| l.fault.is_none()), "every lane of a batch has fault loads, or none does");
                None
            }
        };
        let dt = lanes.each_ref().map(|lane| lane.dt_s);
        let anelastic = AnelasticParams::new(model, &dt);
        assert!(anelastic.is_none() || rupture.is_none(), "bars that crack carry no memory variables or dashpots");
        let mut p = Params {
            model,
            k,
            friction,
            rupture,
            fault,
            anelastic,
            dt,
            damping: [0.0; L],
            body: [[0.0; L]; 3],
            coef: Coefficients { cf: [0.0; L], c2: [0.0; L], cp: [0.0; L] },
        };
        for l in 0..L {
            p.update_coefficients(l);
        }
        p
    }

    fn update_coefficients(&mut self, l: usize) {
        let dt = self.dt[l];
        let a = 0.5 * self.damping[l] * dt;
        self.coef.cf[l] = dt * dt / (1.0 + a);
        self.coef.c2[l] = 2.0 / (1.0 + a);
        self.coef.cp[l] = (1.0 - a) / (1.0 + a);
    }

    /// What the kernels read of the bar stiffness.
    pub fn stiffness(&self) -> StiffnessRef<'_, L> {
        self.k.view(self.model.run_stiffness())
    }

    /// The kernel stiffness of every bar of lane `l` (internal order; a stencil's computed from
    /// its runs and factors).
    pub fn lane_stiffness(&self, l: usize) -> Vec<f64> {
        self.stiffness().lane(self.model.layout(), l)
    }

    /// Time step of lane `l` (s).
    pub fn dt(&self, l: usize) -> f64 {
        self.dt[l]
    }

    /// Mass-proportional damping of lane `l` (1/s).
    pub fn damping(&self, l: usize) -> f64 {
        self.damping[l]
    }

    /// Sets the mass-proportional damping D (1/s) of lane `l`.
    pub fn set_damping(&mut self, l: usize, d: f64) {
        self.damping[l] = d;
        self.update_coefficients(l);
    }

    /// Sets the body acceleration (m/s², e.g. gravity `[0, 0, −g]`) of lane `l`.
    pub fn set_body_acceleration(&mut self, l: usize, b: [f64; 3]) {
        for (c, v) in b.into_iter().enumerate() {
            self.body[c][l] = v;
        }
    }

    /// Body acceleration of lane `l` (m/s²).
    pub fn body_acceleration(&self, l: usize) -> [f64; 3] {
        [self.body[0][l], self.body[1][l], self.body[2][l]]
    }

    /// Body acceleration of every lane, per axis.
    pub fn body(&self) -> &[Lanes<L>; 3] {
        &self.body
    }

    /// Time step of every lane.
    pub fn dts(&self) -> &Lanes<L> {
        &self.dt
    }

    /// Damping of every lane.
    pub fn dampings(&self) -> &Lanes<L> {
        &self.damping
    }

    /// Coefficients of the trial update.
    pub fn coefficients(&self) -> &Coefficients<L> {
        &self.coef
    }
}
