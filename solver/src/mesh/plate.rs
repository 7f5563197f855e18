//! Structured quadrilateral mesh of the plate (half or full), its boundary conditions, the
//! mid-span nodes and the lookup of probe points.

use crate::input::scene::Geometry;
use crate::input::scene::{Ends, MeshSettings, MidSpanNode, Model, Plate, Scene};

/// Nodes and 4-node elements (counter-clockwise). Coordinates in m.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub coords: Vec<[f64; 2]>,
    pub elements: Vec<[u32; 4]>,
}

impl Mesh {
    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    pub fn element_coords(&self, e: usize) -> [[f64; 2]; 4] {
        self.elements[e].map(|n| self.coords[n as usize])
    }

    /// The mean of element `e`'s corners as made, m (where messages say an element is).
    pub fn element_centre(&self, e: usize) -> [f64; 2] {
        let c = self.element_coords(e);
        [0, 1].map(|d| 0.25 * (c[0][d] + c[1][d] + c[2][d] + c[3][d]))
    }

    /// The first element whose deformed shape (coordinates + `u`, 2 dofs per node) has a
    /// corner with a non-positive Jacobian: inverted or collapsed.
    pub fn first_inverted(&self, u: &[f64]) -> Option<usize> {
        self.elements.iter().position(|nodes| {
            let p = nodes.map(|n| {
                let n = n as usize;
                [
                    self.coords[n][0] + u[2 * n],
                    self.coords[n][1] + u[2 * n + 1],
                ]
            });
            (0..4).any(|a| {
                let (next, prev) = (p[(a + 1) % 4], p[(a + 3) % 4]);
                let e1 = [next[0] - p[a][0], next[1] - p[a][1]];
                let e2 = [prev[0] - p[a][0], prev[1] - p[a][1]];
                e1[0] * e2[1] - e1[1] * e2[0] <= 0.0
            })
        })
    }
}

/// The mesh of the plate with what the solver needs to know about it.
#[derive(Debug, Clone)]
pub struct PlateMesh {
    pub mesh: Mesh,
    pub nx: usize,
    pub ny: usize,
    /// `true` for each constrained degree of freedom (2 per node: x, y).
    pub fixed_dofs: Vec<bool>,
    /// Mid-span nodes at the top surface, the mid-plane and the bottom surface.
    pub top: usize,
    pub mid: usize,
    pub bottom: usize,
    /// 2 for the half model (everything reported is for the whole plate), 1 for the full.
    pub symmetry_factor: f64,
    pub model: Model,
    pub length: f64,
}

impl PlateMesh {
    pub fn new(plate: &Plate, settings: &MeshSettings) -> PlateMesh {
        let (nx, ny) = (settings.nx, settings.ny);
        let grid = station_grid(plate);
        let xs = x_stations(plate.length, nx, settings.grading, settings.model, grid);
        let ys = stations(
            std::iter::repeat_n(plate.thickness / ny as f64, ny),
            plate.thickness,
            grid,
        );
        let node = |i: usize, j: usize| i + j * (nx + 1);
        let mut coords = Vec::with_capacity((nx + 1) * (ny + 1));
        for &y in &ys {
            for &x in &xs {
                coords.push([x, y]);
            }
        }
        let i_mid = match settings.model {
            Model::Half => nx,
            Model::Full => nx / 2,
        };
        if settings.distortion > 0.0 {
            distort(&mut coords, &xs, &ys, i_mid, settings.distortion);
        }
        let mut elements = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                elements.push(
                    [
                        node(i, j),
                        node(i + 1, j),
                        node(i + 1, j + 1),
                        node(i, j + 1),
                    ]
                    .map(|n| n as u32),
                );
            }
        }
        let mut fixed_dofs = vec![false; 2 * coords.len()];
        let (fix_x, fix_y) = match plate.ends {
            Ends::Clamped => (true, true),
            Ends::Roller => (true, false),
            Ends::Slider => (false, true),
            Ends::Free => (false, false),
        };
        for j in 0..=ny {
            let support = |dofs: &mut Vec<bool>, n: usize| {
                dofs[2 * n] |= fix_x;
                dofs[2 * n + 1] |= fix_y;
            };
            support(&mut fixed_dofs, node(0, j));
            match settings.model {
                Model::Half => fixed_dofs[2 * node(nx, j)] = true, // symmetry: u_x = 0
                Model::Full => support(&mut fixed_dofs, node(nx, j)),
            }
        }
        PlateMesh {
            mesh: Mesh { coords, elements },
            nx,
            ny,
            fixed_dofs,
            top: node(i_mid, ny),
            mid: node(i_mid, ny / 2),
            bottom: node(i_mid, 0),
            symmetry_factor: match settings.model {
                Model::Half => 2.0,
                Model::Full => 1.0,
            },
            model: settings.model,
            length: plate.length,
        }
    }

    /// The mesh of `scene`'s plate ([`PlateMesh::new`]) in its geometry: in the axisymmetric
    /// one the modelled half-section stands for the whole round plate (its ring), so its
    /// results are not doubled (`symmetry_factor` 1).
    pub fn of_scene(scene: &Scene) -> PlateMesh {
        let mut mesh = PlateMesh::new(&scene.plate, &scene.mesh);
        if scene.geometry == Geometry::Axisymmetric {
            mesh.symmetry_factor = 1.0;
        }
        mesh
    }

    /// The x coordinate of the mid-span line (the half model's symmetry line, the axis of the
    /// axisymmetric geometry), m.
    pub fn mid_span_x(&self) -> f64 {
        self.mesh.coords[self.bottom][0]
    }

    pub fn mid_span_node(&self, which: MidSpanNode) -> usize {
        match which {
            MidSpanNode::MidPlane => self.mid,
            MidSpanNode::TopSurface => self.top,
        }
    }

    /// Top-surface nodes with their tributary lengths along x (half of each adjacent
    /// element edge), m.
    pub fn top_nodes_with_tributary_length(&self) -> Vec<(usize, f64)> {
        let first = self.ny * (self.nx + 1);
        (0..=self.nx)
            .map(|i| {
                let x = |k: usize| self.mesh.coords[first + k][0];
                let left = if i > 0 { x(i) - x(i - 1) } else { 0.0 };
                let right = if i < self.nx { x(i + 1) - x(i) } else { 0.0 };
                (first + i, 0.5 * (left + right))
            })
            .collect()
    }

    /// The point in the modelled part: in the half model, `x > L/2` is mirrored to `L - x`.
    pub fn fold(&self, point: [f64; 2]) -> [f64; 2] {
        match self.model {
            Model::Half if point[0] > 0.5 * self.length => [self.length - point[0], point[1]],
            _ => point,
        }
    }

    /// The first (lowest index) element whose bounding box contains the point.
    pub fn element_containing(&self, point: [f64; 2]) -> Option<usize> {
        let tol = 1e-12 * self.length;
        (0..self.mesh.elements.len()).find(|&e| {
            let c = self.mesh.element_coords(e);
            let (lo, hi) = c.iter().fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(lo, hi), p| {
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1])],
                        [hi[0].max(p[0]), hi[1].max(p[1])],
                    )
                },
            );
            (0..2).all(|k| point[k] >= lo[k] - tol && point[k] <= hi[k] + tol)
        })
    }
}

/// Shifts every interior node (off the boundaries and the mid-span line) by up to
/// `fraction / 2` of the smaller adjacent spacing in each direction, with a fixed
/// pseudo-random pattern (splitmix64 of the node index), so a distorted mesh is reproducible.
fn distort(coords: &mut [[f64; 2]], xs: &[f64], ys: &[f64], i_mid: usize, fraction: f64) {
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    for j in 1..ny {
        for i in (1..nx).filter(|&i| i != i_mid) {
            let n = i + j * (nx + 1);
            let hx = (xs[i + 1] - xs[i]).min(xs[i] - xs[i - 1]);
            let hy = (ys[j + 1] - ys[j]).min(ys[j] - ys[j - 1]);
            coords[n][0] += fraction * hx * (unit_random(2 * n as u64) - 0.5);
            coords[n][1] += fraction * hy * (unit_random(2 * n as u64 + 1) - 0.5);
        }
    }
}

/// A number in [0, 1) from splitmix64 of `seed`.
fn unit_random(seed: u64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Grid step of the stations, m: the spacing of doubles just below the plate's extent
/// rounded up to a power of two, `2^(ceil(log2 extent) - 53)`. Element sizes are rounded to
/// it, so every station, a sum of sizes, is exact, and elements of equal size have equal
/// coordinates relative to their node 0, bit for bit; `length - x` (the mirrored half) is
/// exact too.
///
/// Why: stations summed or divided in floating point (`x += dx`, `t j / n`) give the
/// elements of a uniform row sizes that differ in the last bits, so their geometry and
/// stiffness matrices differ too and none of them can be shared
/// ([`crate::physics::elements::geometry::SharedBatches`] shares equal bits only): a q4-sri element held ~365
/// bytes on the paper's 80 x 16 mesh instead of ~240. Rounding moves an element's size by at
/// most half a step (1.4e-17 m on the 0.2 m plate, 1e-14 of its 80 x 16 elements' height);
/// the node coordinates are the mesh, so every element's geometry is that of its nodes.
fn station_grid(plate: &Plate) -> f64 {
    let extent = plate.length.max(plate.thickness);
    2f64.powi(extent.log2().ceil() as i32 - 53)
}

/// Stations (m) from 0 by element `sizes` (m), each rounded to `grid` (so every partial sum
/// is exact), the last one `end` exactly: the last element takes the rounding's sum.
fn stations(sizes: impl Iterator<Item = f64>, end: f64, grid: f64) -> Vec<f64> {
    let mut at = vec![0.0];
    let mut x = 0.0;
    for size in sizes {
        x += (size / grid).round() * grid;
        at.push(x);
    }
    *at.last_mut().expect("one station at least") = end;
    at
}

/// Node x-coordinates (m) from the clamped end: uniform, or a geometric progression
/// whose largest / smallest element length is `grading`, smallest at mid-span; on `grid`
/// ([`station_grid`]; the far half mirrored, exactly).
fn x_stations(length: f64, nx: usize, grading: f64, model: Model, grid: f64) -> Vec<f64> {
    let half_elements = match model {
        Model::Half => nx,
        Model::Full => nx / 2,
    };
    let ratio = if half_elements > 1 {
        grading.powf(-1.0 / (half_elements - 1) as f64)
    } else {
        1.0
    };
    let sizes: Vec<f64> = (0..half_elements).map(|i| ratio.powi(i as i32)).collect();
    let total: f64 = sizes.iter().sum();
    let half = stations(
        sizes.iter().map(|s| s / total * 0.5 * length),
        0.5 * length,
        grid,
    );
    match model {
        Model::Half => half,
        Model::Full => {
            let mut full = half.clone();
            full.extend(half.iter().rev().skip(1).map(|&x| length - x));
            full
        }
    }
}

/// The paper's plate (200 x 20 mm, 0.2 m wide, clamped) as a q4-sri half model of
/// `nx` x `ny` elements with `grading`: the mesh of the solver's unit tests.
#[cfg(test)]
pub(crate) fn test_plate_mesh(nx: usize, ny: usize, grading: f64) -> PlateMesh {
    let plate = Plate {
        length: 0.2,
        width: 0.2,
        thickness: 0.02,
        ends: Ends::Clamped,
    };
    let settings = MeshSettings {
        nx,
        ny,
        element: crate::input::scene::ElementKind::Q4Sri,
        model: Model::Half,
        grading,
        hourglass: 0.05,
        distortion: 0.0,
    };
    PlateMesh::new(&plate, &settings)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scene::ElementKind;

    fn settings(nx: usize, ny: usize, grading: f64, model: Model) -> MeshSettings {
        MeshSettings {
            nx,
            ny,
            element: ElementKind::Q4Sri,
            model,
            grading,
            hourglass: 0.05,
            distortion: 0.0,
        }
    }

    const PLATE: Plate = Plate {
        length: 0.2,
        width: 0.2,
        thickness: 0.02,
        ends: Ends::Clamped,
    };

    #[test]
    fn graded_half_mesh_spans_the_half_length_with_the_requested_ratio() {
        let m = PlateMesh::new(&PLATE, &settings(10, 2, 4.0, Model::Half));
        let xs: Vec<f64> = (0..=10).map(|i| m.mesh.coords[i][0]).collect();
        assert_eq!(xs[0], 0.0);
        assert_eq!(xs[10], 0.1);
        let first = xs[1] - xs[0];
        let last = xs[10] - xs[9];
        assert!((first / last - 4.0).abs() < 1e-12, "{first} / {last}");
    }

    #[test]
    fn full_mesh_is_symmetric_and_clamped_at_both_ends() {
        let m = PlateMesh::new(&PLATE, &settings(8, 2, 3.0, Model::Full));
        for i in 0..=8 {
            let a = m.mesh.coords[i][0];
            let b = m.mesh.coords[8 - i][0];
            assert_eq!(a + b, 0.2, "mirrored exactly");
        }
        // Mid-span exactly; the mid-plane within the stations' rounding (half a grid step,
        // 2^-56 m here, for the one element below it).
        assert_eq!(m.mesh.coords[m.mid][0], 0.1);
        assert!((m.mesh.coords[m.mid][1] - 0.01).abs() <= 2f64.powi(-56));
        assert!(m.fixed_dofs[2 * 8] && m.fixed_dofs[2 * 8 + 1]);
    }

    /// The uniform 80 x 16 mesh: every element but those of the last column and row has the
    /// same node coordinates relative to its node 0, bit for bit (so their geometry is
    /// shared), within 1e-14 of the exact size; summed in floating point, they were not.
    #[test]
    fn equal_elements_of_a_uniform_mesh_have_equal_relative_coordinates() {
        let m = test_plate_mesh(80, 16, 1.0);
        let relative = |e: usize| {
            let c = m.mesh.element_coords(e);
            c.map(|p| [p[0] - c[0][0], p[1] - c[0][1]])
        };
        let first = relative(0);
        for e in (0..80 * 16).filter(|e| e % 80 != 79 && e / 80 != 15) {
            assert_eq!(relative(e), first, "element {e}");
        }
        // The grid of the 0.2 m plate: the spacing of doubles in [0.125, 0.25). Its worst
        // case, half a step, is 1.1e-14 of these 1.25 mm sizes; measured 8.7e-16 (the
        // quotient's own rounding): 1e-14 is about 10x that, and a coarser grid fails.
        assert_eq!(station_grid(&PLATE), 2f64.powi(-55));
        assert!((first[2][0] - 0.1 / 80.0).abs() < 1e-14 * 0.1 / 80.0);
        assert!((first[2][1] - 0.02 / 16.0).abs() < 1e-14 * 0.02 / 16.0);
        let mut x = 0.0;
        let summed: Vec<f64> = (0..80)
            .map(|_| {
                x += 0.1 / 80.0;
                x
            })
            .collect();
        assert!(
            summed.windows(3).any(|w| w[1] - w[0] != w[2] - w[1]),
            "the old stations"
        );
    }

    #[test]
    fn distortion_moves_only_interior_nodes_and_is_reproducible() {
        let mut s = settings(6, 4, 1.0, Model::Half);
        let plain = PlateMesh::new(&PLATE, &s);
        s.distortion = 0.3;
        let a = PlateMesh::new(&PLATE, &s);
        let b = PlateMesh::new(&PLATE, &s);
        assert_eq!(a.mesh.coords, b.mesh.coords);
        let mut moved = 0;
        for (n, (p, q)) in plain.mesh.coords.iter().zip(&a.mesh.coords).enumerate() {
            let (i, j) = (n % 7, n / 7);
            if i == 0 || i == 6 || j == 0 || j == 4 {
                assert_eq!(p, q, "boundary or mid-span node {n} moved");
            } else if p != q {
                moved += 1;
                assert!(
                    (p[0] - q[0]).abs() <= 0.15 * 0.1 / 6.0 && (p[1] - q[1]).abs() <= 0.15 * 0.005
                );
            }
        }
        assert_eq!(moved, 15);
    }

    #[test]
    fn half_mesh_has_symmetry_at_mid_span_and_finds_probes() {
        let m = PlateMesh::new(&PLATE, &settings(4, 2, 1.0, Model::Half));
        assert!(m.fixed_dofs[2 * 4] && !m.fixed_dofs[2 * 4 + 1]);
        assert_eq!(m.mesh.coords[m.top], [0.1, 0.02]);
        assert!((m.fold([0.15, 0.0])[0] - 0.05).abs() < 1e-15);
        assert_eq!(m.element_containing([0.1, 0.0]), Some(3));
        assert_eq!(m.element_containing([0.01, 0.015]), Some(4));
    }
}
