//! The top displacement split into rocking, slipping, flexural and shearing parts.

use super::mesh;

/// Top-displacement decomposition shared by the dynamic and static analyses:
/// (q, rocking, slipping, flexural, shearing).
pub(super) fn decompose(mesh: &mesh::Mesh, u: &[f64]) -> [f64; 5] {
    let (nx, ny) = (mesh.nx, mesh.ny);
    let row_rotation = |j: usize| {
        let left = mesh.node(0, j);
        let right = mesh.node(nx, j);
        (u[2 * left + 1] - u[2 * right + 1]) / mesh.width
    };
    let q = mesh.top_nodes().iter().map(|&n| u[2 * n]).sum::<f64>() / (nx + 1) as f64;
    let slipping = mesh.base_nodes().iter().map(|&n| u[2 * n]).sum::<f64>() / (nx + 1) as f64;
    let theta0 = row_rotation(0);
    let rocking = theta0 * mesh.height;
    let dy = mesh.height / ny as f64;
    let mut flexural = 0.0;
    let mut previous = 0.0;
    for j in 1..=ny {
        let current = row_rotation(j) - theta0;
        flexural += 0.5 * (previous + current) * dy;
        previous = current;
    }
    let shearing = q - rocking - slipping - flexural;
    [q, rocking, slipping, flexural, shearing]
}
