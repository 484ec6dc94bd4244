//! Computing the points of a study, in parallel with the `parallel` feature, in their order.

/// `f` of every index of `indices`, in order; computed in parallel with the `parallel` feature.
#[cfg(feature = "parallel")]
pub(crate) fn in_order<R: Send>(
    indices: std::ops::Range<usize>,
    f: impl Fn(usize) -> R + Sync + Send,
) -> Vec<R> {
    use rayon::prelude::*;
    indices.into_par_iter().map(f).collect()
}

/// `f` of every index of `indices`, in order.
#[cfg(not(feature = "parallel"))]
pub(crate) fn in_order<R: Send>(
    indices: std::ops::Range<usize>,
    f: impl Fn(usize) -> R + Sync + Send,
) -> Vec<R> {
    indices.map(f).collect()
}
