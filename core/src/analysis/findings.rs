//! The paper's qualitative findings about the SDOF response, measured on a solution's history:
//! Fig. 6 (|s| does not exceed s_n; s dents while the body rocks; r = 0 whenever |q| <= s_n) and
//! Figs. 12-13 (the q-r and s-r relations of book/src/model.md §3).
//!
//! For the exact solution these follow from the model; a solver that changes mode late (Newmark
//! with overshoot compensation) breaks them at the samples taken between crossing and detection,
//! and the numbers here show by how much.

use serde::Serialize;

use crate::integrate::solution::Solution;
use crate::physics::automaton::{Automaton, Mode};

/// One rocking episode: a run of samples in a rocking mode.
#[derive(Debug, Clone, Serialize)]
pub struct Dent {
    /// Time of the first sample of the episode, s.
    pub t_start: f64,
    /// Time of the last sample of the episode, s.
    pub t_end: f64,
    /// "rock-right" or "rock-left".
    pub mode: &'static str,
    /// Largest |r| in the episode, m.
    pub max_abs_r: f64,
    /// Smallest |s| in the episode, m.
    pub min_abs_s: f64,
    /// s_n - min |s|: how deep s dents below the uplift displacement, m.
    pub depth: f64,
}

/// The findings in numbers.
#[derive(Debug, Clone, Serialize)]
pub struct Findings {
    /// s_n, the uplift displacement, m.
    pub s_n: f64,
    /// B, the width (the q at which the body overturns), m.
    pub width: f64,
    /// Largest |s| over the history, m, and its ratio to s_n (the paper: never above 1).
    pub max_abs_s: f64,
    /// Largest |s| divided by s_n.
    pub max_abs_s_over_s_n: f64,
    /// Whether |s| stays within s_n (up to rounding) over the history.
    pub s_never_exceeds_s_n: bool,
    /// Largest |r| over samples with |q| <= s_n (the paper: 0).
    pub max_abs_r_where_abs_q_within_s_n: f64,
    /// Largest ||r| - r(|q|)| while rocking, r(q) the rocking branch (Fig. 12; B (|q| - s_n)/(B - s_n)
    /// in the paper's model, eq. 9b).
    pub max_q_r_relation_residual: f64,
    /// Largest ||s| - s(|r|)| while rocking (Fig. 13; s_n (1 - |r|/B) in the paper's model).
    pub max_s_r_relation_residual: f64,
    /// Rocking episodes with a dent (depth > 0) in s.
    pub rocking_episodes: usize,
    /// How many of the rocking episodes have a dent.
    pub episodes_with_dent: usize,
    /// The rocking episodes, each with its dent.
    pub dents: Vec<Dent>,
}

/// Measures the findings on `solution` of the body whose automaton is `automaton`. The q-r and s-r
/// relations are the automaton's rocking branch, whatever mode a solver recorded at a sample.
pub fn measure(solution: &Solution, automaton: &Automaton) -> Findings {
    let (s_n, b) = (automaton.uplift_displacement(), automaton.width());
    let mut max_abs_s: f64 = 0.0;
    let mut max_r_inside: f64 = 0.0;
    let mut q_r: f64 = 0.0;
    let mut s_r: f64 = 0.0;
    let mut dents: Vec<Dent> = Vec::new();
    let mut open: Option<Dent> = None;
    for x in &solution.samples {
        max_abs_s = max_abs_s.max(x.s.abs());
        if x.q.abs() <= s_n {
            max_r_inside = max_r_inside.max(x.r.abs());
        }
        let rocking = matches!(x.mode, Mode::RockRight | Mode::RockLeft);
        if rocking {
            let branch_r = automaton.rocking_part(Mode::RockRight, x.q.abs());
            q_r = q_r.max((x.r.abs() - branch_r).abs());
            s_r = s_r.max((x.s.abs() - automaton.flexural_part_at_rocking_part(x.r.abs())).abs());
            let episode = open.get_or_insert(Dent {
                t_start: x.t,
                t_end: x.t,
                mode: x.mode.name(),
                max_abs_r: 0.0,
                min_abs_s: f64::INFINITY,
                depth: 0.0,
            });
            episode.t_end = x.t;
            episode.max_abs_r = episode.max_abs_r.max(x.r.abs());
            episode.min_abs_s = episode.min_abs_s.min(x.s.abs());
            episode.depth = s_n - episode.min_abs_s;
        } else if let Some(done) = open.take() {
            dents.push(done);
        }
    }
    dents.extend(open);
    Findings {
        s_n,
        width: b,
        max_abs_s,
        max_abs_s_over_s_n: max_abs_s / s_n,
        s_never_exceeds_s_n: max_abs_s <= s_n * (1.0 + 1e-9),
        max_abs_r_where_abs_q_within_s_n: max_r_inside,
        max_q_r_relation_residual: q_r,
        max_s_r_relation_residual: s_r,
        rocking_episodes: dents.len(),
        episodes_with_dent: dents.iter().filter(|d| d.depth > 0.0).count(),
        dents,
    }
}
