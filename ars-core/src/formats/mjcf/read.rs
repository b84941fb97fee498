//! Reading an MJCF file into its parsed [`Model`]: the elements
//! ARS reads, what it skips or refuses and where (a [`Problem`](super::problem::Problem) at a line).

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};

use super::MAX_CONTACT_PAIRS;
use super::contact::{collision_bits, contact_parameters_unused, geom_contact, pair_contact};
use super::defaults::{Attrs, Compiler, Defaults, frame, orientation, read_defaults};
use super::flags::Flags;
use super::frame::{Named, Placed, Replicas};
use super::hfield::{Hfield, hfield_asset};
use super::include::{Files, Includes, Tree, gather};
use super::mass::{bounded, mass_of_geoms, scale_masses, total_mass};
use super::meshes::{MeshAsset, load_mesh, mesh_assets};
use super::model::{Body, Geom, GeomKind, Joint, JointKind, MeshGeom, Model, Pair, Site};
use super::problem::{Parsed, problem, skip_or_refuse};
use super::{MjcfOptions, SITE_SIZE};
use crate::sensors::TouchZone;

/// Reads the model's elements.
pub(super) struct Reader<'d, 'a, 'input> {
    pub(super) tree: &'d Tree<'a, 'input>,
    pub(super) compiler: Compiler,
    pub(super) defaults: &'d Defaults,
    pub(super) skip: bool,
    pub(super) skipped: Vec<String>,
    pub(super) bodies: usize,
    pub(super) joints: usize,
    /// The `<asset><mesh>`es by name.
    pub(super) meshes: HashMap<String, MeshAsset>,
    /// The `<asset><hfield>`s by name.
    pub(super) hfields: HashMap<String, std::sync::Arc<Hfield>>,
    /// The meshes loaded so far, by name.
    pub(super) loaded: HashMap<String, std::sync::Arc<MeshGeom>>,
    /// The `<asset><material>`s' colours, by name.
    pub(super) materials: HashMap<String, [f64; 4]>,
    /// Their files, each read once.
    pub(super) files: crate::formats::MeshCache,
    /// The main file's folder.
    pub(super) dir: std::path::PathBuf,
    /// Where the `<frame>`s around the element being read place it in its body.
    pub(super) place: Isometry3<f64>,
    /// The suffix the `<replicate>`s around it add to its name ("" outside them).
    pub(super) suffix: String,
    /// The innermost replicate copy it is in (0 outside them).
    pub(super) copy: usize,
    /// The replicated names, and their copies' suffixes.
    pub(super) replicas: Replicas,
    /// The elements and copies `<replicate>`s made so far.
    pub(super) replicated: usize,
}

impl<'a, 'input> Reader<'_, 'a, 'input> {
    pub(super) fn unsupported(&mut self, node: &roxmltree::Node<'_, '_>, what: &str) -> Parsed<()> {
        skip_or_refuse(problem(node, format!("{what} is not supported")), self.skip, &mut self.skipped)
    }

    /// A `<geom>`, or `None` when it is of a type ARS skips.
    pub(super) fn geom(&mut self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<Option<Geom>> {
        let a = Attrs::new(node, self.defaults, class);
        let Some((kind, frame)) = self.geom_shape(&a)? else { return Ok(None) };
        let mass = a.number("mass")?;
        if mass.is_some_and(|m| m < 0.0) {
            return Err(problem(&node, "mass must not be negative"));
        }
        // Outside `<compiler inertiagrouprange>`, a geom adds nothing to its body's mass.
        let [low, high] = self.compiler.inertia_groups;
        let mass = if (low..=high).contains(&a.number("group")?.unwrap_or(0.0)) { mass } else { Some(0.0) };
        let density = a.number("density")?.unwrap_or(1000.0);
        if density < 0.0 {
            return Err(problem(&node, "density must not be negative"));
        }
        let bits = (collision_bits(&a, "contype")?, collision_bits(&a, "conaffinity")?);
        if let GeomKind::Mesh(mesh) = &kind
            && mesh.hull.is_none()
            && bits != (0, 0)
        {
            let name = a.get("mesh").unwrap_or_default();
            return Err(problem(
                &node,
                format!("the mesh {name:?} is flat: it has no convex hull to collide as (MuJoCo refuses it too)"),
            ));
        }
        let contact = geom_contact(&a)?;
        let unused: Vec<&str> = ["margin", "gap"].into_iter().filter(|k| a.get(k).is_some()).collect();
        contact_parameters_unused(&node, &unused, &mut self.skipped);
        let name = node.attribute("name").map(|n| self.renamed(Named::Geom, n));
        // Its own rgba (or its class's), else its material's colour, as MuJoCo draws it.
        let rgba = match a.fixed::<4>("rgba")? {
            Some(rgba) => Some(rgba),
            None => a.get("material").and_then(|m| self.materials.get(m)).copied(),
        };
        let frame = self.place * frame;
        Ok(Some(Geom { kind, frame, mass, density, rgba, bits, contact, name }))
    }

    /// A geom's shape (its type and size) and its frame (the one `fromto` gives, if
    /// any), or `None` when its type is skipped.
    fn geom_shape(&mut self, a: &Attrs<'_, '_>) -> Parsed<Option<(GeomKind, Isometry3<f64>)>> {
        let node = a.node;
        let kind_name = a.get("type").unwrap_or("sphere");
        let size = a.numbers("size")?.unwrap_or_default();
        let fromto = a.fixed::<6>("fromto")?;
        let size_at = |i: usize| -> Parsed<f64> {
            match size.get(i) {
                Some(s) if *s > 0.0 => Ok(*s),
                Some(s) => Err(problem(&node, format!("size {s} must be positive"))),
                None => Err(problem(&node, format!("a {kind_name} needs {} size numbers", i + 1))),
            }
        };
        let mut frame = frame(a, &self.compiler)?;
        let kind = match kind_name {
            "mesh" => GeomKind::Mesh(self.mesh(&node, a.get("mesh"))?),
            "hfield" => {
                let name = a.get("hfield").ok_or_else(|| problem(&node, "an hfield geom needs an hfield"))?;
                let field = self.hfields.get(name);
                GeomKind::Hfield(
                    field.ok_or_else(|| problem(&node, format!("no <hfield> asset is called {name:?}")))?.clone(),
                )
            }
            "plane" => GeomKind::Plane,
            "sphere" => GeomKind::Sphere(size_at(0)?),
            "capsule" | "cylinder" => {
                let (r, h) = match fromto {
                    Some(f) => {
                        let (placed, half_length) = fromto_frame(&node, f)?;
                        frame = placed;
                        (size_at(0)?, half_length)
                    }
                    None => (size_at(0)?, size_at(1)?),
                };
                if kind_name == "capsule" { GeomKind::Capsule(r, h) } else { GeomKind::Cylinder(r, h) }
            }
            "box" | "ellipsoid" => {
                // Placed by `fromto` as MuJoCo places them: the first size across, twice,
                // the half-length along z.
                let half_sizes = match fromto {
                    Some(f) => {
                        let (placed, half_length) = fromto_frame(&node, f)?;
                        frame = placed;
                        Vector3::new(size_at(0)?, size_at(0)?, half_length)
                    }
                    None => Vector3::new(size_at(0)?, size_at(1)?, size_at(2)?),
                };
                if kind_name == "box" { GeomKind::Box(half_sizes) } else { GeomKind::Ellipsoid(half_sizes) }
            }
            other => {
                self.unsupported(&node, &format!("a geom of type {other:?}"))?;
                return Ok(None);
            }
        };
        Ok(Some((kind, frame)))
    }

    pub(super) fn joint(&mut self, node: roxmltree::Node<'_, '_>, class: &str, free: bool) -> Parsed<Joint> {
        self.joints += 1;
        let a = Attrs::new(node, self.defaults, class);
        let kind = match (free, a.get("type").unwrap_or("hinge")) {
            (true, _) | (_, "free") => JointKind::Free,
            (_, "hinge") => JointKind::Hinge,
            (_, "slide") => JointKind::Slide,
            (_, "ball") => JointKind::Ball,
            (_, other) => return Err(problem(&node, format!("a joint of type {other:?} is not supported"))),
        };
        let name = match a.node.attribute("name") {
            Some(name) => self.renamed(Named::Joint, name),
            None => format!("joint{}", self.joints - 1),
        };
        let axis = Vector3::from(a.fixed::<3>("axis")?.unwrap_or([0.0, 0.0, 1.0]));
        if axis.norm() == 0.0 {
            return Err(problem(&node, "axis is zero"));
        }
        // A hinge's positions are angles, in the compiler's unit.
        let angle = if kind == JointKind::Hinge && self.compiler.degrees { 1f64.to_radians() } else { 1.0 };
        let given = a.fixed::<2>("range")?;
        // As MuJoCo: a free joint is never limited (its class's `limited` aside); "auto"
        // limits a joint whose range is not empty (`<compiler autolimits>`).
        let limited = match a.get("limited") {
            _ if kind == JointKind::Free => false,
            Some("true") => true,
            Some("false") => false,
            _ => self.compiler.autolimits && given.is_some_and(|[lo, hi]| lo < hi),
        };
        let range = match (limited, given) {
            (true, Some([lo, hi])) => {
                if lo > hi {
                    return Err(problem(&node, format!("range {lo} {hi} is reversed")));
                }
                Some((lo * angle, hi * angle))
            }
            (true, None) => return Err(problem(&node, "is limited but has no range")),
            _ => None,
        };
        let damping = a.number("damping")?.unwrap_or(0.0);
        if damping < 0.0 {
            return Err(problem(&node, "damping must not be negative"));
        }
        let armature = a.number("armature")?.unwrap_or(0.0);
        if armature < 0.0 {
            return Err(problem(&node, "armature must not be negative"));
        }
        let mut reference = a.number("ref")?.unwrap_or(0.0) * angle;
        let mut spring = (a.number("stiffness")?.unwrap_or(0.0), a.number("springref")?.unwrap_or(0.0) * angle);
        let frictionloss = a.number("frictionloss")?.unwrap_or(0.0);
        if spring.0 < 0.0 || frictionloss < 0.0 {
            return Err(problem(&node, "stiffness and frictionloss must not be negative"));
        }
        // A ball's or a free joint's has no one position: ARS's springs and reference
        // positions are of hinges and slides (their frictionloss is a motor's: build.rs).
        if matches!(kind, JointKind::Ball | JointKind::Free) {
            for (attribute, value) in [("ref", reference), ("stiffness", spring.0)] {
                if value != 0.0 {
                    self.unsupported(&node, &format!("{attribute} on a ball or free joint"))?;
                }
            }
            (reference, spring) = (0.0, (0.0, 0.0));
        }
        let limit_solref = a.fixed::<2>("solreflimit")?.unwrap_or([0.02, 1.0]);
        let limit_dmax = a.numbers("solimplimit")?.and_then(|s| s.get(1).copied()).unwrap_or(0.95);
        Ok(Joint {
            name,
            kind,
            limit_softness: (limit_solref, limit_dmax),
            pos: (self.place * nalgebra::Point3::from(a.fixed::<3>("pos")?.unwrap_or([0.0; 3]))).coords,
            axis: self.place.rotation * axis.normalize(),
            range,
            damping,
            armature,
            reference,
            spring,
            frictionloss,
        })
    }

    pub(super) fn body(&mut self, node: roxmltree::Node<'a, 'input>, class: &str) -> Parsed<Body> {
        self.bodies += 1;
        let index = self.bodies;
        let a = Attrs::new(node, self.defaults, class);
        let class = node.attribute("childclass").unwrap_or(class).to_string();
        let name = match node.attribute("name") {
            Some(name) => self.renamed(Named::Body, name),
            None => format!("body{index}"),
        };
        let mut body = Body {
            name,
            frame: self.place * frame(&a, &self.compiler)?,
            mass: None,
            geoms: Vec::new(),
            joints: Vec::new(),
            children: Vec::new(),
            sites: Vec::new(),
            principal: None,
            mocap: a.get("mocap") == Some("true"),
        };
        let mut inertial = None;
        let mut principal = None;
        for Placed { node: child, class, frame, suffix, copy } in self.placed_children(node, &class)? {
            (self.place, self.suffix, self.copy) = (frame, suffix, copy);
            match child.tag_name().name() {
                "geom" => body.geoms.extend(self.geom(child, &class)?),
                "joint" => body.joints.push(self.joint(child, &class, false)?),
                "freejoint" => body.joints.push(self.joint(child, &class, true)?),
                "body" => {
                    let inner = self.body(child, &class)?;
                    if inner.mocap {
                        return Err(problem(&child, "a mocap body must be a child of the world body (as MuJoCo says)"));
                    }
                    body.children.push(inner)
                }
                "inertial" => {
                    inertial = Some(self.inertial(child, &class)?);
                    principal = self.principal_axes(child, &class)?;
                }
                "site" => body.sites.extend(self.site(child, &class)?),
                "camera" | "light" => {}
                other => self.unsupported(&child, &format!("<{other}> in a body"))?,
            }
        }
        let from_geoms = match self.compiler.from_geom {
            Some(always) => always,
            None => inertial.is_none(),
        };
        let mass = if from_geoms { mass_of_geoms(&body.geoms) } else { inertial.filter(|m| m.0 > 0.0) };
        body.mass = bounded(mass, self.compiler.bounds);
        body.principal = if from_geoms { None } else { principal };
        if body.mocap && !body.joints.is_empty() {
            return Err(problem(
                &node,
                "a mocap body cannot have joints (as MuJoCo says): it is moved by set_mocap_pose",
            ));
        }
        if body.joints.len() > 1 && body.joints.iter().any(|j| j.kind == JointKind::Free) {
            return Err(problem(&node, "a free joint cannot be combined with other joints in one body"));
        }
        // A free joint's armature would be mass along some directions only: ODE's mass
        // is the same along all.
        for j in body.joints.iter().filter(|j| j.armature > 0.0 && j.kind == JointKind::Free) {
            self.skipped.push(format!(
                "<joint> {:?} in body {:?}: the armature {} of a free joint is not modelled (ODE's mass is the same in every direction)",
                j.name, body.name, j.armature,
            ));
        }
        Ok(body)
    }

    /// The mesh asset `name` (loaded once), for a geom at `node`.
    fn mesh(&mut self, node: &roxmltree::Node<'_, '_>, name: Option<&str>) -> Parsed<std::sync::Arc<MeshGeom>> {
        let name = name.ok_or_else(|| problem(node, "a mesh geom needs a mesh"))?;
        if let Some(mesh) = self.loaded.get(name) {
            return Ok(mesh.clone());
        }
        let asset =
            self.meshes.get(name).ok_or_else(|| problem(node, format!("no <mesh> asset is called {name:?}")))?;
        let folder = match &self.compiler.meshdir {
            Some(meshdir) => self.dir.join(meshdir),
            None => self.dir.clone(),
        };
        let mesh =
            load_mesh(asset, &folder, &mut self.files).map_err(|e| problem(node, format!("the mesh {name:?}: {e}")))?;
        let mesh = std::sync::Arc::new(mesh);
        self.loaded.insert(name.to_string(), mesh.clone());
        Ok(mesh)
    }

    /// A `<site>`, or `None` when it has no name (no sensor can name it) or is skipped.
    pub(super) fn site(&mut self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<Option<Site>> {
        let a = Attrs::new(node, self.defaults, class);
        let Some(name) = node.attribute("name") else { return Ok(None) };
        let name = self.renamed(Named::Site, name);
        let mut size = a.numbers("size")?.unwrap_or_default();
        // A site of size 0 is a point, as MuJoCo takes it (frames and sensors need no
        // size; a touch sensor on it is refused, having no zone).
        if let Some(s) = size.iter().find(|s| !(s.is_finite() && **s >= 0.0)) {
            return Err(problem(&node, format!("size {s} must be 0 or more")));
        }
        // Placed by `fromto` as a geom is: centred between the points, its z axis along
        // them, its half-length theirs.
        let mut frame = frame(&a, &self.compiler)?;
        let kind = a.get("type").unwrap_or("sphere");
        if let Some(f) = a.fixed::<6>("fromto")? {
            let (placed, half_length) = fromto_frame(&node, f)?;
            frame = placed;
            let along = if matches!(kind, "box" | "ellipsoid") { 2 } else { 1 };
            size.resize(size.len().max(along + 1), SITE_SIZE);
            size[along] = half_length;
        }
        let at = |i: usize| size.get(i).copied().unwrap_or(SITE_SIZE);
        let zone = match kind {
            "sphere" => TouchZone::Sphere { radius: at(0) },
            "capsule" => TouchZone::Capsule { radius: at(0), half_length: at(1) },
            "cylinder" => TouchZone::Cylinder { radius: at(0), half_length: at(1) },
            "box" => TouchZone::Box { half_extents: Vector3::new(at(0), at(1), at(2)) },
            "ellipsoid" => TouchZone::Ellipsoid { radii: Vector3::new(at(0), at(1), at(2)) },
            other => {
                self.unsupported(&node, &format!("a site of type {other:?}"))?;
                return Ok(None);
            }
        };
        Ok(Some(Site { name, frame: self.place * frame, zone, welded_from: None }))
    }

    /// The turn of an `<inertial>`'s principal axes from its body's frame: its
    /// orientation when it gives `diaginertia` (MuJoCo's `body_iquat`), `None` for a
    /// `fullinertia` (MuJoCo diagonalises it).
    pub(super) fn principal_axes(
        &self,
        node: roxmltree::Node<'_, '_>,
        class: &str,
    ) -> Parsed<Option<UnitQuaternion<f64>>> {
        let a = Attrs::new(node, self.defaults, class);
        if a.get("diaginertia").is_none() {
            return Ok(None);
        }
        Ok(Some(self.place.rotation * orientation(&a, &self.compiler)?))
    }

    /// `{what}range` when `{what}limited` says it applies ("true", or "auto" with a
    /// range and `<compiler autolimits>`).
    pub(super) fn limited(&self, a: &Attrs<'_, '_>, what: &str) -> Parsed<Option<[f64; 2]>> {
        let range = a.fixed::<2>(&format!("{what}range"))?;
        Ok(match a.get(&format!("{what}limited")).unwrap_or("auto") {
            "true" => Some(range.ok_or_else(|| problem(&a.node, format!("{what}limited needs a {what}range")))?),
            "auto" if self.compiler.autolimits => range,
            _ => None,
        })
    }

    pub(super) fn inertial(
        &mut self,
        node: roxmltree::Node<'_, '_>,
        class: &str,
    ) -> Parsed<(f64, Vector3<f64>, Matrix3<f64>)> {
        let a = Attrs::new(node, self.defaults, class);
        let mass = a.number("mass")?.ok_or_else(|| problem(&node, "needs a mass"))?;
        // A zero mass is a massless body, as MuJoCo reads it (welded, or refused if it moves).
        if mass < 0.0 {
            return Err(problem(&node, format!("mass {mass} must not be negative")));
        }
        let frame = self.place * frame(&a, &self.compiler)?;
        let local = match (a.fixed::<3>("diaginertia")?, a.fixed::<6>("fullinertia")?) {
            (Some(d), None) => Matrix3::from_diagonal(&Vector3::from(d)),
            (None, Some(f)) => crate::formats::inertia_tensor(f),
            _ => return Err(problem(&node, "needs one of diaginertia and fullinertia")),
        };
        let r = frame.rotation.to_rotation_matrix();
        Ok((mass, frame.translation.vector, crate::formats::turned_inertia(&r, &local)))
    }
}

/// The frame of a capsule or cylinder placed by `fromto` (centred between its two
/// points, its z axis from the first to the second) and its half-length.
fn fromto_frame(node: &roxmltree::Node<'_, '_>, f: [f64; 6]) -> Parsed<(Isometry3<f64>, f64)> {
    let (from, to) = (Vector3::new(f[0], f[1], f[2]), Vector3::new(f[3], f[4], f[5]));
    let along = to - from;
    if along.norm() == 0.0 {
        return Err(problem(node, "fromto's two points are the same"));
    }
    let turn = UnitQuaternion::rotation_between(&Vector3::z(), &along)
        .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
    Ok((Isometry3::from_parts(Translation3::from((from + to) / 2.0), turn), along.norm() / 2.0))
}

/// Reads the model from the text of a file (`name` resolves its includes).
pub(super) fn read(name: &str, text: &str, options: &MjcfOptions) -> Parsed<Model> {
    let mut files = Files::new();
    let mut includes = Includes::new();
    gather(name, text.to_string(), &mut files, &mut includes, &mut vec![name.to_string()])?;
    let documents = files
        .iter()
        .map(|(_, text)| roxmltree::Document::parse(text).expect("parsed once already"))
        .collect::<Vec<_>>();
    let tree = Tree { documents: &documents, includes: &includes };
    read_nodes(name, &tree, options).map_err(|mut p| {
        // A problem in an included file names it.
        if p.file.is_none()
            && let Some(index) = tree.file_at(p.document).filter(|&i| i > 0)
        {
            p.file = Some(files[index].0.clone());
        }
        p
    })
}

/// Reads the model from its files: first the sections the others depend on
/// (compiler, defaults, assets, options), then the bodies, actuators, contacts and
/// sensors.
pub(super) fn read_nodes(name: &str, tree: &Tree<'_, '_>, options: &MjcfOptions) -> Parsed<Model> {
    let root = tree.documents[0].root_element();
    let nodes = tree.elements(root);
    let mut schema_skips = Vec::new();
    super::schema::check_attributes(tree, root, options.skip_unsupported, &mut schema_skips)?;
    let mut settings = read_settings(tree, &nodes)?;
    let flags = std::mem::take(&mut settings.flags);
    let materials = material_colors(&settings.material_nodes, &settings.defaults)?;
    let meshes = mesh_assets(&settings.mesh_nodes, &settings.defaults)?;
    let dir = Path::new(name).parent().map(Path::to_path_buf).unwrap_or_default();
    let folder = match &settings.compiler.meshdir {
        Some(meshdir) => dir.join(meshdir),
        None => dir.clone(),
    };
    let mut hfields = HashMap::new();
    for &node in &settings.hfield_nodes {
        let (name, field) = hfield_asset(&Attrs::new(node, &settings.defaults, "main"), &folder)?;
        hfields.insert(name, std::sync::Arc::new(field));
    }
    let mut reader = Reader {
        compiler: settings.compiler,
        defaults: &settings.defaults,
        skip: options.skip_unsupported,
        skipped: schema_skips,
        bodies: 0,
        joints: 0,
        meshes,
        materials,
        loaded: HashMap::new(),
        files: crate::formats::MeshCache::default(),
        tree,
        dir,
        hfields,
        place: Isometry3::identity(),
        suffix: String::new(),
        copy: 0,
        replicas: Replicas::new(),
        replicated: 0,
    };
    let mut model = Model {
        name: root.attribute("model").unwrap_or("").to_string(),
        timestep: settings.timestep,
        gravity: settings.gravity,
        magnetic: settings.magnetic,
        ..Model::default()
    };
    for &node in &nodes {
        reader.section(node, &mut model)?;
    }
    super::frame::replicate_references(&mut model, &reader.replicas).map_err(|text| problem(&root, text))?;
    super::weld::weld_jointless(&mut model);
    reader.check_sensors(&mut model)?;
    model.skipped = reader.skipped;
    flags.apply(&mut model);
    if let Some(total) = reader.compiler.total_mass {
        let now = total_mass(&model.bodies);
        if now > 0.0 {
            scale_masses(&mut model.bodies, total / now);
        }
    }
    Ok(model)
}

/// What the first pass reads: the sections every other element depends on.
struct Settings<'a, 'input> {
    compiler: Compiler,
    defaults: Defaults,
    timestep: Option<f64>,
    gravity: Option<Vector3<f64>>,
    /// `<option magnetic>`, MuJoCo's `(0, −0.5, 0)` if not given.
    magnetic: Vector3<f64>,
    /// `<option><flag>`s.
    flags: Flags,
    /// The `<asset><mesh>`es, read once every default class is known.
    mesh_nodes: Vec<roxmltree::Node<'a, 'input>>,
    /// The `<asset><material>`s, read once every default class is known.
    material_nodes: Vec<roxmltree::Node<'a, 'input>>,
    /// The `<asset><hfield>`s.
    hfield_nodes: Vec<roxmltree::Node<'a, 'input>>,
}

/// The first pass over the top-level elements: `<compiler>`, `<default>`, `<asset>`
/// and `<option>`, wherever they are in the file.
fn read_settings<'a, 'input>(
    tree: &Tree<'a, 'input>,
    nodes: &[roxmltree::Node<'a, 'input>],
) -> Parsed<Settings<'a, 'input>> {
    let mut settings = Settings {
        compiler: Compiler::default(),
        defaults: Defaults::new(),
        timestep: None,
        gravity: None,
        magnetic: Vector3::new(0.0, -0.5, 0.0),
        flags: Flags::default(),
        mesh_nodes: Vec::new(),
        material_nodes: Vec::new(),
        hfield_nodes: Vec::new(),
    };
    for &node in nodes {
        match node.tag_name().name() {
            "compiler" => read_compiler(node, &mut settings.compiler)?,
            "default" => read_defaults(tree, node, &HashMap::new(), &mut settings.defaults),
            "asset" => {
                settings.mesh_nodes.extend(tree.elements(node).into_iter().filter(|c| c.has_tag_name("mesh")));
                settings.material_nodes.extend(tree.elements(node).into_iter().filter(|c| c.has_tag_name("material")));
                settings.hfield_nodes.extend(tree.elements(node).into_iter().filter(|c| c.has_tag_name("hfield")));
            }
            "option" => {
                let a = Attrs { node, class: None };
                settings.timestep = a.number("timestep")?;
                settings.gravity = a.fixed::<3>("gravity")?.map(Vector3::from);
                if let Some(m) = a.fixed::<3>("magnetic")? {
                    settings.magnetic = Vector3::from(m);
                }
                for flag in tree.elements(node).into_iter().filter(|c| c.has_tag_name("flag")) {
                    settings.flags.read(flag);
                }
            }
            _ => {}
        }
    }
    Ok(settings)
}

/// Reads a `<compiler>`'s settings into `compiler`.
fn read_compiler(node: roxmltree::Node<'_, '_>, compiler: &mut Compiler) -> Parsed<()> {
    if let Some(angle) = node.attribute("angle") {
        compiler.degrees = angle != "radian";
    }
    if let Some(seq) = node.attribute("eulerseq") {
        let axes: Vec<u8> = seq
            .chars()
            .filter_map(|c| match c.to_ascii_lowercase() {
                'x' => Some(0),
                'y' => Some(1),
                'z' => Some(2),
                _ => None,
            })
            .collect();
        compiler.eulerseq =
            axes.try_into().map_err(|_| problem(&node, format!("eulerseq {seq:?} must be three of x, y, z")))?;
        compiler.extrinsic = seq.chars().all(|c| c.is_ascii_uppercase());
    }
    if let Some(auto) = node.attribute("autolimits") {
        compiler.autolimits = auto == "true";
    }
    if let Some(v) = node.attribute("inertiafromgeom") {
        compiler.from_geom = match v {
            "true" => Some(true),
            "false" => Some(false),
            _ => None,
        };
    }
    if let Some([low, high]) = (Attrs { node, class: None }).fixed::<2>("inertiagrouprange")? {
        compiler.inertia_groups = [low, high];
    }
    if let Some(total) = node.attribute("settotalmass") {
        compiler.total_mass = match total.parse::<f64>() {
            Ok(m) if m > 0.0 && m.is_finite() => Some(m),
            Ok(_) => None,
            Err(_) => return Err(problem(&node, format!("settotalmass {total:?} is not a number"))),
        };
    }
    let a = Attrs { node, class: None };
    for (k, name) in ["boundmass", "boundinertia"].into_iter().enumerate() {
        match a.number(name)? {
            Some(bound) if bound < 0.0 => return Err(problem(&node, format!("{name} must not be negative"))),
            Some(bound) if k == 0 => compiler.bounds.0 = bound,
            Some(bound) => compiler.bounds.1 = bound,
            None => {}
        }
    }
    if let Some(dir) = node.attribute("meshdir").or(node.attribute("assetdir")) {
        compiler.meshdir = Some(dir.to_string());
    }
    if node.attribute("coordinate").is_some_and(|c| c != "local") {
        return Err(problem(&node, "coordinate=\"global\" is not supported (MuJoCo removed it too)"));
    }
    Ok(())
}

/// The materials' colours by name, with their classes' defaults (read by now,
/// wherever they are).
fn material_colors(nodes: &[roxmltree::Node<'_, '_>], defaults: &Defaults) -> Parsed<HashMap<String, [f64; 4]>> {
    let mut materials = HashMap::new();
    for &node in nodes {
        let a = Attrs::new(node, defaults, "main");
        if let (Some(name), Some(rgba)) = (node.attribute("name"), a.fixed::<4>("rgba")?) {
            materials.insert(name.to_string(), rgba);
        }
    }
    Ok(materials)
}

impl<'a, 'input> Reader<'_, 'a, 'input> {
    /// The second pass: reads a top-level element into `model` (the first pass's are
    /// passed over).
    fn section(&mut self, node: roxmltree::Node<'a, 'input>, model: &mut Model) -> Parsed<()> {
        let tree = self.tree;
        match node.tag_name().name() {
            "worldbody" => self.world_body(node, model)?,
            "actuator" => {
                for (i, child) in tree.elements(node).into_iter().enumerate() {
                    if let Some(actuator) = self.actuator(child, i)? {
                        model.actuators.push(actuator);
                    }
                }
            }
            "compiler" | "default" | "option" | "visual" | "asset" | "statistic" | "size" | "custom" => {}
            "contact" => self.contacts(node, model)?,
            "equality" => self.equalities(node, model)?,
            "tendon" => self.tendons(node)?,
            "keyframe" => {
                for (i, key) in tree.elements(node).into_iter().enumerate() {
                    model.keyframes.push(super::keyframe::keyframe(key, i)?);
                }
            }
            "sensor" => {
                for (i, child) in tree.elements(node).into_iter().enumerate() {
                    if let Some(sensor) = self.sensor(child, i)? {
                        model.sensors.push(sensor);
                        model.sensor_places.push(problem(&child, ""));
                    }
                }
            }
            other => self.unsupported(&node, &format!("<{other}>"))?,
        }
        Ok(())
    }

    /// The `<worldbody>`: its geoms, bodies and sites.
    fn world_body(&mut self, node: roxmltree::Node<'a, 'input>, model: &mut Model) -> Parsed<()> {
        for Placed { node: child, class, frame, suffix, copy } in self.placed_children(node, "main")? {
            (self.place, self.suffix, self.copy) = (frame, suffix, copy);
            match child.tag_name().name() {
                "geom" => model.world_geoms.extend(self.geom(child, &class)?),
                "body" => model.bodies.push(self.body(child, &class)?),
                "site" => model.world_sites.extend(self.site(child, &class)?.map(|s| s.name)),
                "camera" | "light" => {}
                other => self.unsupported(&child, &format!("<{other}> in the world body"))?,
            }
        }
        (self.place, self.suffix, self.copy) = (Isometry3::identity(), String::new(), 0);
        Ok(())
    }

    /// A `<contact>` section: its exclusions and its pairs (up to
    /// [`MAX_CONTACT_PAIRS`]).
    fn contacts(&mut self, node: roxmltree::Node<'a, 'input>, model: &mut Model) -> Parsed<()> {
        for child in self.tree.elements(node) {
            let needs = |attr: &str| {
                child.attribute(attr).map(str::to_string).ok_or_else(|| problem(&child, format!("needs a {attr}")))
            };
            match child.tag_name().name() {
                "exclude" => model.excluded.push((needs("body1")?, needs("body2")?)),
                "pair" => {
                    if model.pairs.len() == MAX_CONTACT_PAIRS {
                        self.unsupported(&child, &format!("a contact pair beyond the first {MAX_CONTACT_PAIRS}"))?;
                        continue;
                    }
                    let a = Attrs::new(child, self.defaults, child.attribute("class").unwrap_or("main"));
                    let (contact, unused) = pair_contact(&a)?;
                    contact_parameters_unused(&child, &unused, &mut self.skipped);
                    model.pairs.push(Pair { geom1: needs("geom1")?, geom2: needs("geom2")?, contact });
                }
                other => self.unsupported(&child, &format!("<{other}> in <contact>"))?,
            }
        }
        Ok(())
    }
}
