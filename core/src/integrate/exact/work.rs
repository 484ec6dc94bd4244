//! The energy books' work integrals over the pieces of a sampled history, as quadratic forms.
//!
//! Over a piece [end - h, end] of a flow, the Taylor series of f and of x' about the end
//! ([`Flow::work_series`]) are linear in the data at the end ([`Flow::work_data`]: x, x' and
//! the forcing's Taylor data), so the integrals of f x' and of x'^2 over the piece are quadratic
//! forms of those data, whose matrices depend only on the flow's k, c and kind of forcing
//! ([`Flow::work_key`]) and on h. The history's pieces between samples all have the grid's
//! spacing, and consecutive flows mostly share their key (free motion and a sine's flows
//! between events; a record's flows of one mode), so the matrices are built once, from the
//! series of each unit datum, and each sample's integrals cost two small matrix products
//! instead of the products of two series. A piece's length differs from the matrices' by the
//! rounding of the grid's times (i dt, rounded: up to an ulp of t, which late in a long run is
//! hundreds of ulps of h); the sliver of that length at the piece's start is added as its length
//! times the integrands there (f x' and x'^2 at the end of the piece before, which the run
//! keeps). What that leaves out is the sliver's length squared times the integrands' rate, a
//! share of the piece's integral of the order of (sliver / h)^2: below 1e-24 on the paper's
//! example (slivers up to 1e-15 s on h = 5 ms), 1e-12 at worst within the limits of a run (a
//! sliver of a few ulps of 1e4 s on a piece of 10 ms cut in 200 for a stiff body), far below
//! the books' rounding either way.

use super::flow::{Flow, WorkKey, RECIPROCALS, WORK_TERMS};
use super::kept::Kept;
use super::rounding::near;

/// Largest data of a flow whose work integrals are kept as quadratic forms: x, x' and a cubic's
/// four coefficients (the ramp; a record's pieces are linear and a sinusoid has f and f'). The
/// Ricker wavelet's pieces of degree 18 are integrated as series, piece by piece.
pub(crate) const FORM_LEN: usize = 6;

/// Forms kept at once: a run goes back and forth between its modes (before uplift and
/// rocking), and between kinds of forcing (the ramp's cubic, then the sine).
const KEPT: usize = 4;

/// The forms a run has built, the last [`KEPT`] of them.
#[derive(Debug, Default)]
pub(crate) struct FormCache {
    kept: Kept<WorkForms, KEPT>,
}

impl FormCache {
    /// The kept forms that serve a piece of `flow` of length `h` ending at `t`, if any; else,
    /// given the `nominal` length of such pieces (the grid's spacing), new forms of that length
    /// (None where the flow's data are too long for forms, or h is not near `nominal`).
    pub fn serve(
        &mut self,
        flow: &Flow,
        h: f64,
        t: f64,
        nominal: Option<f64>,
    ) -> Option<&WorkForms> {
        let key = flow.work_key();
        self.kept.serve(
            |f: &WorkForms| f.key == key && near(h, f.h, t),
            || WorkForms::new(flow, nominal.filter(|&n| near(h, n, t))?),
        )
    }

    /// A handle on the forms that served last ([`FormCache::get`]).
    pub fn last(&self) -> (usize, usize) {
        self.kept.last()
    }

    /// The forms a handle from [`FormCache::last`] names, while no other forms have been built.
    pub fn get(&self, handle: (usize, usize)) -> Option<&WorkForms> {
        self.kept.get(handle)
    }
}

/// The work integrals over pieces of length `h` of the flows with one [`WorkKey`], as
/// quadratic forms of the data at a piece's end.
#[derive(Debug, Clone)]
pub(crate) struct WorkForms {
    key: WorkKey,
    h: f64,
    len: usize,
    /// The integral of f x' is data . (force data), that of x'^2 is data . (square data).
    force: [[f64; FORM_LEN]; FORM_LEN],
    square: [[f64; FORM_LEN]; FORM_LEN],
}

impl WorkForms {
    /// The forms of `flow`'s key over pieces of length `h`; None where its data are too long.
    fn new(flow: &Flow, h: f64) -> Option<Self> {
        let key = flow.work_key();
        let len = key.len();
        if len > FORM_LEN {
            return None;
        }
        let terms = flow.work_terms(h);
        let mut series = [([0.0; WORK_TERMS], [0.0; WORK_TERMS]); FORM_LEN];
        for (i, unit) in series.iter_mut().enumerate().take(len) {
            let mut data = [0.0; FORM_LEN];
            data[i] = 1.0;
            *unit = flow.work_series(&data[..len], h, terms);
        }
        let mut forms = WorkForms {
            key,
            h,
            len,
            force: [[0.0; FORM_LEN]; FORM_LEN],
            square: [[0.0; FORM_LEN]; FORM_LEN],
        };
        for (i, (f_i, v_i)) in series[..len].iter().enumerate() {
            let (f_i, v_i) = (&f_i[..terms], &v_i[..terms]);
            // f is the forcing's alone: x and x' (the first two data) do not enter it.
            if i >= 2 {
                for (j, (_, v_j)) in series[..len].iter().enumerate() {
                    // As in Flow::work_integrals: v was scaled by -h, and ds = h d sigma.
                    forms.force[i][j] = -products(f_i, &v_j[..terms]);
                }
            }
            for (j, (_, v_j)) in series[..len].iter().enumerate().skip(i) {
                let square = products(v_i, &v_j[..terms]) / h;
                forms.square[i][j] = square;
                forms.square[j][i] = square;
            }
        }
        Some(forms)
    }

    /// The length of the pieces the forms were built for, s.
    pub fn length(&self) -> f64 {
        self.h
    }

    /// The integrals of f x' and of x'^2 over the piece of length `h` (the forms' own but for
    /// the rounding of the grid's times) that ends with `data`, with the integrands f x' and
    /// x'^2 at its `start`.
    pub fn integrals(&self, data: &[f64; FORM_LEN], h: f64, start: [f64; 2]) -> (f64, f64) {
        let (force, square) = match self.len {
            3 => self.forms::<3>(data),
            4 => self.forms::<4>(data),
            5 => self.forms::<5>(data),
            _ => self.forms::<FORM_LEN>(data),
        };
        // The sliver at the piece's start beyond (or short of) the forms' length.
        let extra = h - self.h;
        (force + extra * start[0], square + extra * start[1])
    }

    /// The two quadratic forms of the first N data (N the forms' length; unused data are 0).
    #[inline(always)]
    fn forms<const N: usize>(&self, data: &[f64; FORM_LEN]) -> (f64, f64) {
        let data = &data[..N];
        let dot = |row: &[f64; FORM_LEN]| {
            row[..N]
                .iter()
                .zip(data)
                .fold(0.0, |sum, (m, d)| sum + m * d)
        };
        let form = |matrix: &[[f64; FORM_LEN]; FORM_LEN], first: usize| {
            data.iter()
                .zip(matrix)
                .skip(first)
                .fold(0.0, |sum, (d, row)| sum + d * dot(row))
        };
        // f is the forcing's alone: the rows of x and x' (the first two) are zero.
        let (force, square) = (form(&self.force, 2), form(&self.square, 0));
        (force, square)
    }
}

/// sum over i, j of a_i b_j / (i + j + 1): the integral over [0, 1] of the product of the
/// polynomials with coefficients a and b.
fn products(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .enumerate()
        .map(|(i, &ai)| {
            ai * b
                .iter()
                .zip(&RECIPROCALS[i..])
                .map(|(&bj, &w)| bj * w)
                .sum::<f64>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::double_double::DoubleDouble as Dd;
    use crate::floor::ClosedForm;
    use crate::physics::automaton::LinearForm;

    /// A flow of the linear form (k, c, q_eq, beta) under `floor` from (q, q') at t = 2 s.
    fn flow(linear: (f64, f64, f64, f64), floor: &ClosedForm, q: f64, v: f64) -> Flow {
        let (stiffness, damping, equilibrium, participation) = linear;
        let form = LinearForm {
            stiffness,
            damping,
            equilibrium,
            participation,
        };
        Flow::new(
            &form,
            floor,
            2.0,
            0.0,
            Dd::exact(q),
            Dd::exact(v),
            floor.until.min(3.0),
            None,
        )
    }

    /// The integrals of f x' and x'^2 over [end - h, end] by 12-point Gauss-Legendre from the
    /// closed form's points and the floor's own a(t) (f = -beta a): apart from the series the
    /// forms are built from. And the scale they are compared at, h (|f| + |x'|) |x'|.
    fn quadrature(flow: &Flow, floor: &ClosedForm, beta: f64, end: f64, h: f64) -> [f64; 3] {
        let mut sums = [0.0; 3];
        for (x, w) in crate::physics::flexural_shape::gauss_legendre(12) {
            let t = end - h + h * x;
            let (p, f) = (flow.point(t), -beta * floor.shape.value(t));
            sums[0] += w * h * f * p.v;
            sums[1] += w * h * p.v * p.v;
            sums[2] = sums[2].max(h * (f.abs() + p.v.abs()) * p.v.abs());
        }
        sums
    }

    /// A floor, a linear form (k, c, q_eq, beta), and q and q' at the anchor.
    type Case = (ClosedForm, (f64, f64, f64, f64), f64, f64);

    /// Flows of every form the forms serve: before uplift under a sine, rocking in free motion
    /// (the saddle), and the series form under a record's linear piece and the ramp's cubic.
    fn cases() -> Vec<Case> {
        let pre = (394.0, 1.98, 0.0, 1.57);
        let rocking = (-3.1, -0.16, 0.175, 1.57);
        vec![
            (ClosedForm::sine(5.0, 1.0), pre, 0.004, -0.03),
            (
                ClosedForm::exact(f64::INFINITY, crate::floor::Shape::Rest),
                rocking,
                0.05,
                0.2,
            ),
            (
                ClosedForm::polynomial(2.0, &[1.3, -40.0], 2.02),
                pre,
                -0.002,
                0.05,
            ),
            (
                ClosedForm::polynomial(1.9, &[0.0, 0.5, -3.0, 12.0], 2.02),
                rocking,
                0.03,
                -0.1,
            ),
        ]
    }

    /// Each sample's integrals from the forms equal an independent quadrature of the closed
    /// form to 1e-14 of their scale, on pieces of the grid's spacing anywhere in the flow.
    #[test]
    fn the_forms_give_the_integrals_of_the_closed_form() {
        for (floor, linear, q, v) in cases() {
            let flow = flow(linear, &floor, q, v);
            let h = 0.005;
            let forms = WorkForms::new(&flow, h).expect("forms for every case");
            for end in [2.005, 2.0111, 2.0193] {
                let (p, force) = flow.point_with_force(end);
                let (force_work, square) = forms.integrals(&flow.work_data(&p, force), h, [0.0; 2]);
                let [f_ref, s_ref, scale] = quadrature(&flow, &floor, linear.3, end, h);
                assert!(
                    (force_work - f_ref).abs() <= 1e-14 * scale
                        && (square - s_ref).abs() <= 1e-14 * scale,
                    "{floor:?} at {end}: ({force_work:e}, {square:e}) against \
                     ({f_ref:e}, {s_ref:e}), scale {scale:e}"
                );
            }
        }
    }

    /// A piece a billionth longer than the forms' own (far beyond the rounding of the grid's
    /// times, which the forms take): the sliver is added from the integrands at the piece's
    /// start, leaving the sliver's length squared times their rate. Without it the error would
    /// be a billionth of the piece's integrals.
    #[test]
    fn a_piece_longer_than_the_forms_adds_its_sliver() {
        for (floor, linear, q, v) in cases() {
            let flow = flow(linear, &floor, q, v);
            let (h, end) = (0.005, 2.0111);
            let longer = h * (1.0 + 1e-9);
            let forms = WorkForms::new(&flow, h).expect("forms for every case");
            let (p, force) = flow.point_with_force(end);
            let first = flow.point(end - longer);
            let f_first = -linear.3 * floor.shape.value(end - longer);
            let start = [f_first * first.v, first.v * first.v];
            let (force_work, square) = forms.integrals(&flow.work_data(&p, force), longer, start);
            let [f_ref, s_ref, scale] = quadrature(&flow, &floor, linear.3, end, longer);
            let [f_short, s_short, _] = quadrature(&flow, &floor, linear.3, end, h);
            assert!(
                (f_ref - f_short).abs().max((s_ref - s_short).abs()) > 1e-12 * scale,
                "{floor:?}: the sliver is too small to tell"
            );
            assert!(
                (force_work - f_ref).abs() <= 1e-14 * scale
                    && (square - s_ref).abs() <= 1e-14 * scale,
                "{floor:?}: ({force_work:e}, {square:e}) against ({f_ref:e}, {s_ref:e}), \
                 scale {scale:e}"
            );
        }
    }

    /// The cache serves a piece within the rounding of the grid's times and the same key, builds
    /// no forms for a piece that is not of the grid's spacing, and builds them at the spacing
    /// itself.
    #[test]
    fn the_cache_serves_only_its_own_key_and_length() {
        let cases = cases();
        let (floor, linear, q, v) = &cases[0];
        let flow_a = flow(*linear, floor, *q, *v);
        let (floor_b, linear_b, q_b, v_b) = &cases[1];
        let flow_b = flow(*linear_b, floor_b, *q_b, *v_b);
        let mut cache = FormCache::default();
        // 2.01 - 2.005 rounded: within an ulp of t, not 0.005 itself.
        let rounded = 2.01 - 2.005;
        assert_ne!(rounded, 0.005);
        assert!(cache.serve(&flow_a, rounded, 2.01, None).is_none());
        assert!(cache.serve(&flow_a, 0.0051, 2.01, Some(0.005)).is_none());
        // Built at the nominal length, whichever span asked first.
        let built = cache
            .serve(&flow_a, rounded, 2.01, Some(0.005))
            .map(|f| f.h);
        assert_eq!(built, Some(0.005));
        assert!(cache.serve(&flow_a, 0.005, 2.01, None).is_some());
        let longer = 0.005 * (1.0 + 1e-9);
        assert!(cache.serve(&flow_a, longer, 2.01, None).is_none());
        assert!(cache.serve(&flow_b, 0.005, 2.01, None).is_none());
    }
}
