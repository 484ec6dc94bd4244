//! Whatever the text of a model file, reading it gives a model or an error, never a panic.

use flexrock::model::{Model, Overrides};
use proptest::prelude::*;

const REFERENCE: &str = include_str!("../models/ichinose1986.toml");

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,400}") {
        let _ = Model::from_toml_str(&text, &Overrides::default());
    }

    #[test]
    fn edited_reference_never_panics(
        edits in proptest::collection::vec((0usize..2000, "[-0-9.eE+a-z=\"\\n\\[\\] ]{0,6}"), 0..6)
    ) {
        let mut text = REFERENCE.to_string();
        for (at, insert) in edits {
            let mut at = at % (text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            let end = (at + insert.len()).min(text.len());
            let end = (end..=text.len()).find(|&e| text.is_char_boundary(e)).unwrap_or(text.len());
            text.replace_range(at..end, &insert);
        }
        if let Ok(model) = Model::from_toml_str(&text, &Overrides::default()) {
            // A model that passes validation has a body the model means something for.
            prop_assert!(model.constants.uplift_displacement < model.body.width);
            prop_assert!(model.constants.zeta_landing < 1.0);
            prop_assert!(model.duration > 0.0);
        }
    }
}
