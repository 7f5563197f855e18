//! The one model factory: element x material x kernel -> a [`PlateModel`], handed to a
//! [`UseModel`] (the time loop, a benchmark), so the dispatch over the generic element and
//! material types is written once. [`AnyFormulation`] with [`with_formulation!`] is the one
//! dispatch over elements alone (static checks that need no material).

use crate::input::error::{Error, Result, SourceLocation};
use crate::input::scene::Geometry;
use crate::input::scene::{ElementKind, Kinematics, Scene};
use crate::lanes::simd::KernelPath;
use crate::mesh::{Mesh, PlateMesh};
use crate::physics::elements::axisymmetric::Axisymmetric;
use crate::physics::elements::element::{Formulation, FullQ4, OnePointQ4, SelectiveQ4};
use crate::physics::elements::finite_element::{FiniteResponse, UpdatedLagrangian};
use crate::physics::materials::finite_material::Finite;
use crate::physics::materials::material::{ConstitutiveModel, Elastic, VonMises};
use crate::physics::materials::rate_plasticity::ViscoPlastic;
use crate::time_loop::plate_model::PlateModel;

/// One of the element formulations, chosen at run time.
pub enum AnyFormulation {
    Full(FullQ4),
    Sri(SelectiveQ4),
    OnePoint(OnePointQ4),
}

impl AnyFormulation {
    /// The `kind` formulation on `mesh`, out-of-plane `width` (m); `hourglass` is the
    /// Flanagan-Belytschko coefficient of `q4-1pt`, scaled by `elastic`'s P-wave modulus.
    pub fn new(
        kind: ElementKind,
        mesh: &Mesh,
        width: f64,
        hourglass: f64,
        elastic: &Elastic,
    ) -> Result<AnyFormulation> {
        Ok(match kind {
            ElementKind::Q4Full => AnyFormulation::Full(FullQ4::new(mesh, width)?),
            ElementKind::Q4Sri => AnyFormulation::Sri(SelectiveQ4::new(mesh, width)?),
            ElementKind::Q4OnePoint => AnyFormulation::OnePoint(OnePointQ4::new(
                mesh,
                width,
                hourglass,
                elastic.p_modulus(),
            )?),
        })
    }
}

/// `with_formulation!(any, f => body)`: `body` with `f` bound to the concrete formulation
/// inside an [`AnyFormulation`] (by value, reference or mutable reference, as `any` is).
#[macro_export]
macro_rules! with_formulation {
    ($any:expr, $f:ident => $body:expr) => {
        match $any {
            $crate::time_loop::model::AnyFormulation::Full($f) => $body,
            $crate::time_loop::model::AnyFormulation::Sri($f) => $body,
            $crate::time_loop::model::AnyFormulation::OnePoint($f) => $body,
        }
    };
}

/// The material model and how the elastic internal forces are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernel {
    /// What `simulate` runs: von Mises when the material has plasticity, else [`Kernel::Elastic`].
    Solver,
    /// Elastic, by the faster path of the element ([`Formulation::STIFFNESS_MATRIX_PAYS`]):
    /// precomputed element stiffness matrices for q4-full and q4-sri, the stresses for
    /// q4-1pt (`impact-bench throughput` kernels, 80 x 16 paper mesh, 1 thread, two runs of
    /// 2026-11-25 after the one-point element took Flanagan and Belytschko's centroid form:
    /// q4-1pt 4.7 ns through the stresses against 5.7 ns through `K_e u_e`, whose one-point
    /// hourglass energy costs a second pass; q4-sri 5.1-5.3 ns through `K_e u_e` against 17.1-17.4
    /// ns).
    Elastic,
    /// Elastic, always with precomputed element stiffness matrices.
    ElasticStiffnessMatrix,
    /// Elastic, always through the stresses (strain -> stress -> `B^T s`).
    ElasticStressPath,
    /// Von Mises plasticity (the material must have `plasticity`), with the elastic screen
    /// where the stiffness matrix pays (elements that never yielded and stay elastic take
    /// `K_e u_e`: [`crate::kernels::elastic_screen`]).
    Plastic,
}

/// What to do with a built model, for every element x material combination.
pub trait UseModel {
    type Output;
    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        model: PlateModel<F, M>,
    ) -> Self::Output;
}

/// Builds the model of `scene` on `mesh` (its element, its material, `kernel`) and hands it
/// to `user`, with the batched kernels on this processor's best instruction set.
pub fn build<U: UseModel>(
    scene: &Scene,
    mesh: &PlateMesh,
    kernel: Kernel,
    user: U,
) -> Result<U::Output> {
    build_on(scene, mesh, kernel, KernelPath::fastest(), user)
}

/// [`build`] with the element kernels on `path` (e.g. [`KernelPath::Scalar`], the reference
/// the batched kernels are tested and benchmarked against).
pub fn build_on<U: UseModel>(
    scene: &Scene,
    mesh: &PlateMesh,
    kernel: Kernel,
    path: KernelPath,
    user: U,
) -> Result<U::Output> {
    let m = &scene.material;
    let elastic = Elastic::new(m.youngs_modulus, m.poisson_ratio);
    if scene.geometry == Geometry::Axisymmetric {
        return with_ring(scene, mesh, kernel, path, user);
    }
    let formulation = AnyFormulation::new(
        scene.mesh.element,
        &mesh.mesh,
        scene.plate.width,
        scene.mesh.hourglass,
        &elastic,
    )?;
    let request = Request {
        scene,
        mesh,
        kernel,
        path,
    };
    if scene.kinematics == Kinematics::Finite {
        no_stiffness_matrix(
            scene,
            kernel,
            ("kinematics", "finite"),
            "the stiffness-matrix kernel is a small-strain one: use the stress path",
        )?;
    }
    with_formulation!(formulation, f => with_kinematics(f, request, user))
}

/// The refusal of the stiffness-matrix kernel where the scene's `(field, value)` rules it
/// out (`why`: what to use instead).
fn no_stiffness_matrix(
    scene: &Scene,
    kernel: Kernel,
    (field, value): (&str, &str),
    why: &str,
) -> Result<()> {
    if kernel == Kernel::ElasticStiffnessMatrix {
        return Err(Error::invalid(
            SourceLocation::file(&scene.source),
            field,
            value,
            why,
        ));
    }
    Ok(())
}

/// [`build_on`] in the axisymmetric geometry, about the mid-span line, in either kinematics.
fn with_ring<U: UseModel>(
    scene: &Scene,
    mesh: &PlateMesh,
    kernel: Kernel,
    path: KernelPath,
    user: U,
) -> Result<U::Output> {
    no_stiffness_matrix(scene, kernel, ("geometry", "axisymmetric"), "the stiffness-matrix kernel drops rigid translations, and a ring's radial translation strains it: use the stress path")?;
    let m = &scene.material;
    let p_modulus = Elastic::new(m.youngs_modulus, m.poisson_ratio).p_modulus();
    let (axis, hourglass) = (mesh.mid_span_x(), scene.mesh.hourglass);
    let request = Request {
        scene,
        mesh,
        kernel,
        path,
    };
    match scene.mesh.element {
        ElementKind::Q4Full => with_kinematics(
            Axisymmetric::<FullQ4>::new(&mesh.mesh, axis, hourglass, p_modulus)?,
            request,
            user,
        ),
        ElementKind::Q4Sri => with_kinematics(
            Axisymmetric::<SelectiveQ4>::new(&mesh.mesh, axis, hourglass, p_modulus)?,
            request,
            user,
        ),
        ElementKind::Q4OnePoint => with_kinematics(
            Axisymmetric::<OnePointQ4>::new(&mesh.mesh, axis, hourglass, p_modulus)?,
            request,
            user,
        ),
    }
}

/// `formulation` (plane or ring) in the scene's kinematics: as it is in small strain, under
/// [`UpdatedLagrangian`] in finite deformation.
fn with_kinematics<F: MaterialOf + FiniteResponse, U: UseModel>(
    formulation: F,
    request: Request,
    user: U,
) -> Result<U::Output> {
    match request.scene.kinematics {
        Kinematics::Small => with_material(formulation, request, user),
        Kinematics::Finite => with_material(UpdatedLagrangian(formulation), request, user),
    }
}

/// The material model a formulation runs with: the model itself in small strain, the model
/// with a kinematic memory ([`Finite`]) under finite deformation.
pub trait MaterialOf: Formulation {
    type Material<M: ConstitutiveModel>: ConstitutiveModel;
    fn material<M: ConstitutiveModel>(m: M) -> Self::Material<M>;
}

macro_rules! small_strain_material {
    ($($f:ty),*) => {$(
        impl MaterialOf for $f {
            type Material<M: ConstitutiveModel> = M;
            fn material<M: ConstitutiveModel>(m: M) -> M {
                m
            }
        }
    )*};
}
small_strain_material!(
    FullQ4,
    SelectiveQ4,
    OnePointQ4,
    Axisymmetric<FullQ4>,
    Axisymmetric<SelectiveQ4>,
    Axisymmetric<OnePointQ4>
);

impl<F: FiniteResponse> MaterialOf for UpdatedLagrangian<F> {
    type Material<M: ConstitutiveModel> = Finite<M>;
    fn material<M: ConstitutiveModel>(m: M) -> Finite<M> {
        Finite(m)
    }
}

/// A plastic model handed to `user`. Elastic points at elastic cost where the stiffness
/// product is cheaper than a plastic point that stays elastic (F::STIFFNESS_MATRIX_PAYS; not
/// for one point, whose stress path is the cheaper one).
fn with_plastic<F: Formulation, M: ConstitutiveModel, U: UseModel>(
    formulation: F,
    material: M,
    mesh: &PlateMesh,
    density: f64,
    path: KernelPath,
    user: U,
) -> U::Output {
    let model = PlateModel::new(formulation, material, mesh, density).with_kernel_path(path);
    user.use_model(if F::STIFFNESS_MATRIX_PAYS {
        model.with_elastic_screen()
    } else {
        model
    })
}

/// What [`build`] was asked for, handed on to the material stage.
struct Request<'a> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    kernel: Kernel,
    path: KernelPath,
}

fn with_material<F: MaterialOf, U: UseModel>(
    formulation: F,
    Request {
        scene,
        mesh,
        kernel,
        path,
    }: Request,
    user: U,
) -> Result<U::Output> {
    let m = &scene.material;
    let plastic_kernel = matches!(kernel, Kernel::Solver | Kernel::Plastic);
    if let Some(rate) = ViscoPlastic::new(m).filter(|_| plastic_kernel) {
        let rate = F::material(rate);
        return Ok(with_plastic(formulation, rate, mesh, m.density, path, user));
    }
    if let Some(plastic) = VonMises::new(m).filter(|_| plastic_kernel) {
        let plastic = F::material(plastic);
        return Ok(with_plastic(
            formulation,
            plastic,
            mesh,
            m.density,
            path,
            user,
        ));
    }
    if kernel == Kernel::Plastic {
        return Err(Error::invalid(
            SourceLocation::file(&scene.source),
            "material.plasticity",
            "none",
            "the plastic kernel needs a material with plasticity",
        ));
    }
    let stiffness_matrix = match kernel {
        Kernel::ElasticStressPath => false,
        Kernel::ElasticStiffnessMatrix => true,
        _ => F::STIFFNESS_MATRIX_PAYS,
    };
    let elastic = Elastic::new(m.youngs_modulus, m.poisson_ratio);
    let model =
        PlateModel::new(formulation, F::material(elastic), mesh, m.density).with_kernel_path(path);
    Ok(user.use_model(if stiffness_matrix {
        model.with_linear_kernel(&elastic)
    } else {
        model
    }))
}
