//! The Nelder-Mead simplex search both maximum likelihood fits use: two parameters, a smooth
//! function, no derivatives needed.

/// Most evaluations of one search.
const EVALUATION_BUDGET: usize = 20_000;

/// The minimum of `f` near `start`, first steps `step`: the simplex search with the standard
/// coefficients (reflection 1, expansion 2, contraction 1/2, shrink 1/2), restarted from its
/// result until a restart no longer moves it, which guards against a collapsed simplex.
pub fn minimize(f: impl Fn([f64; 2]) -> f64, start: [f64; 2], step: [f64; 2]) -> [f64; 2] {
    let mut best = start;
    let mut value = f(best);
    for _ in 0..20 {
        let next = simplex(&f, best, step);
        let next_value = f(next);
        let moved = (next[0] - best[0]).abs().max((next[1] - best[1]).abs());
        if next_value <= value {
            best = next;
            value = next_value;
        }
        if moved < 1e-13 {
            break;
        }
    }
    best
}

fn simplex(f: &impl Fn([f64; 2]) -> f64, start: [f64; 2], step: [f64; 2]) -> [f64; 2] {
    let mut points = [
        start,
        [start[0] + step[0], start[1]],
        [start[0], start[1] + step[1]],
    ];
    let mut values = points.map(f);
    let mut evaluations = 3;
    let at =
        |a: [f64; 2], b: [f64; 2], t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
    while evaluations < EVALUATION_BUDGET {
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
        points = order.map(|i| points[i]);
        values = order.map(|i| values[i]);
        let size = (points[1][0] - points[0][0])
            .abs()
            .max((points[1][1] - points[0][1]).abs())
            .max((points[2][0] - points[0][0]).abs())
            .max((points[2][1] - points[0][1]).abs());
        if size < 1e-14 * (1.0 + points[0][0].abs().max(points[0][1].abs())) {
            break;
        }
        let centroid = at(points[0], points[1], 0.5);
        let reflected = at(centroid, points[2], -1.0);
        let fr = f(reflected);
        evaluations += 1;
        if fr < values[0] {
            let expanded = at(centroid, points[2], -2.0);
            let fe = f(expanded);
            evaluations += 1;
            (points[2], values[2]) = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < values[1] {
            (points[2], values[2]) = (reflected, fr);
        } else {
            let contracted = if fr < values[2] {
                at(centroid, reflected, 0.5)
            } else {
                at(centroid, points[2], 0.5)
            };
            let fc = f(contracted);
            evaluations += 1;
            if fc < values[2].min(fr) {
                (points[2], values[2]) = (contracted, fc);
            } else {
                for i in 1..3 {
                    points[i] = at(points[0], points[i], 0.5);
                    values[i] = f(points[i]);
                }
                evaluations += 2;
            }
        }
    }
    let mut best = 0;
    for i in 1..3 {
        if values[i] < values[best] {
            best = i;
        }
    }
    points[best]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_minimum_of_rosenbrock() {
        let f = |x: [f64; 2]| (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2);
        let m = minimize(f, [-1.2, 1.0], [0.1, 0.1]);
        assert!(
            (m[0] - 1.0).abs() < 1e-7 && (m[1] - 1.0).abs() < 1e-7,
            "{m:?}"
        );
    }
}
