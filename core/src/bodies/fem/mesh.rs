//! Structured rectangular mesh of the body: `nx` elements across the width, `ny` up the height.
//!
//! Node (i, j), i = 0..=nx from the left edge, j = 0..=ny from the base, has index
//! `j (nx + 1) + i` and dofs `2 index` (x) and `2 index + 1` (y). The base nodes are therefore
//! nodes `0..=nx` and their dofs are the first `2 (nx + 1)` dofs.

#[derive(Debug, Clone)]
pub(crate) struct Mesh {
    pub nx: usize,
    pub ny: usize,
    pub width: f64,
    pub height: f64,
    /// Undeformed coordinates (x, y) of every node, metres.
    pub coords: Vec<[f64; 2]>,
    /// Element connectivity, counter-clockwise from the lower left corner.
    pub elements: Vec<[usize; 4]>,
}

impl Mesh {
    pub fn rectangle(width: f64, height: f64, nx: usize, ny: usize) -> Self {
        let mut coords = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                coords.push([width * i as f64 / nx as f64, height * j as f64 / ny as f64]);
            }
        }
        let mut elements = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let n0 = j * (nx + 1) + i;
                elements.push([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1]);
            }
        }
        Self {
            nx,
            ny,
            width,
            height,
            coords,
            elements,
        }
    }

    pub fn node(&self, i: usize, j: usize) -> usize {
        j * (self.nx + 1) + i
    }

    pub fn node_count(&self) -> usize {
        self.coords.len()
    }

    pub fn dof_count(&self) -> usize {
        2 * self.coords.len()
    }

    pub fn base_nodes(&self) -> Vec<usize> {
        (0..=self.nx).map(|i| self.node(i, 0)).collect()
    }

    pub fn top_nodes(&self) -> Vec<usize> {
        (0..=self.nx).map(|i| self.node(i, self.ny)).collect()
    }

    /// Half-bandwidth of the assembled matrices (largest |dof_a - dof_b| within an element).
    pub fn half_bandwidth(&self) -> usize {
        self.elements
            .iter()
            .map(|e| {
                let lo = e.iter().min().copied().unwrap_or(0);
                let hi = e.iter().max().copied().unwrap_or(0);
                2 * (hi - lo) + 1
            })
            .max()
            .unwrap_or(1)
    }

    pub fn element_coords(&self, e: usize) -> [[f64; 2]; 4] {
        self.elements[e].map(|n| self.coords[n])
    }

    pub fn element_dofs(&self, e: usize) -> [usize; 8] {
        let n = self.elements[e];
        [
            2 * n[0],
            2 * n[0] + 1,
            2 * n[1],
            2 * n[1] + 1,
            2 * n[2],
            2 * n[2] + 1,
            2 * n[3],
            2 * n[3] + 1,
        ]
    }
}
