//! Limits that make every run end: a cap on steps and on events per simulated second, and a
//! stop for a cascade of events in a vanishing time (a Zeno-like chatter, or a defect).
//!
//! The caps are far above what any sound run needs (the paper's example takes about 3000 steps
//! and 20 events over 6 s at rtol = 1e-10; a 60 s record at rtol = 1e-10 about 2e5 steps), so
//! reaching one means the run would not end in any useful time.

/// Steps allowed before any simulated time has passed.
pub const BASE_STEPS: usize = 200_000;
/// Further steps allowed per simulated second.
pub const STEPS_PER_SECOND: f64 = 1e6;
/// Events allowed before any simulated time has passed.
pub const BASE_EVENTS: usize = 1_000;
/// Further events allowed per simulated second.
pub const EVENTS_PER_SECOND: f64 = 1e4;
/// A cascade: this many events ...
pub const CASCADE_EVENTS: usize = 50;
/// ... within this many seconds.
pub const CASCADE_SPAN: f64 = 1e-9;

/// Counts a run's steps and events against the caps.
#[derive(Debug)]
pub(crate) struct RunBudget {
    events: usize,
    /// Times of the last [`CASCADE_EVENTS`] events (a ring).
    recent: [f64; CASCADE_EVENTS],
}

impl Default for RunBudget {
    fn default() -> Self {
        Self::new()
    }
}

impl RunBudget {
    /// A budget with no events spent.
    pub fn new() -> Self {
        RunBudget {
            events: 0,
            recent: [f64::NEG_INFINITY; CASCADE_EVENTS],
        }
    }

    /// Checks the step count `steps` reached at time `t`.
    pub fn step(&self, t: f64, steps: usize) -> Result<(), String> {
        let allowed = BASE_STEPS as f64 + STEPS_PER_SECOND * t.max(0.0);
        if steps as f64 > allowed {
            return Err(format!(
                "{steps} steps by t = {t:.6} s, over the cap of {BASE_STEPS} + {STEPS_PER_SECOND:e} per \
                 simulated second; the run would not end in a useful time (a tolerance too tight for \
                 the excitation, or an excitation too violent for the model)"
            ));
        }
        Ok(())
    }

    /// Books an event at time `t`.
    pub fn event(&mut self, t: f64) -> Result<(), String> {
        // The ring holds the last CASCADE_EVENTS times; after this one is put in, the next slot
        // holds the time CASCADE_EVENTS - 1 events back, which opens the window.
        self.recent[self.events % CASCADE_EVENTS] = t;
        let oldest = self.recent[(self.events + 1) % CASCADE_EVENTS];
        self.events += 1;
        if t - oldest < CASCADE_SPAN {
            return Err(format!(
                "a cascade of {CASCADE_EVENTS} events within {:.3e} s (from t = {oldest} s to {t} s): \
                 the body chatters on a guard faster than the model can resolve",
                t - oldest
            ));
        }
        let allowed = BASE_EVENTS as f64 + EVENTS_PER_SECOND * t.max(0.0);
        if self.events as f64 > allowed {
            return Err(format!(
                "{} events by t = {t:.6} s, over the cap of {BASE_EVENTS} + {EVENTS_PER_SECOND:e} per \
                 simulated second",
                self.events
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cascade_is_stopped_and_spread_events_are_not() {
        let mut budget = RunBudget::new();
        for k in 0..1000 {
            budget.event(k as f64 * 1e-3).unwrap();
        }
        let mut budget = RunBudget::new();
        let outcome: Result<Vec<()>, String> = (0..CASCADE_EVENTS)
            .map(|k| budget.event(1.0 + k as f64 * 1e-12))
            .collect();
        let message = outcome.unwrap_err();
        assert!(message.contains("cascade of 50 events"), "{message}");
    }

    #[test]
    fn steps_and_events_are_capped_per_simulated_second() {
        let budget = RunBudget::new();
        assert!(budget.step(1.0, 1_000_000).is_ok());
        assert!(budget.step(0.0, BASE_STEPS + 1).is_err());
        let mut budget = RunBudget::new();
        let mut failed = None;
        for k in 0..5000 {
            if let Err(m) = budget.event(1e-3 + k as f64 * 1e-8) {
                failed = Some((k, m));
                break;
            }
        }
        let (k, message) = failed.expect("the event cap was never reached");
        assert!(
            (BASE_EVENTS - 1..BASE_EVENTS + 20).contains(&k),
            "stopped after {k} events"
        );
        assert!(message.contains("over the cap"), "{message}");
    }
}
