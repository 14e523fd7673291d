//! Embree 3 (the system library) on the same triangles and rays: only with
//! `--features embree`.

use viewray_geometry::{MeshData, Ray};

/// An Embree scene of triangle meshes, with its default build quality.
pub(crate) struct Embree {
    // Declared before the device so that it is released first.
    scene: embree3::Scene<'static>,
    _device: embree3::Device,
}

impl Embree {
    /// Builds a scene of one triangle mesh per entry of `meshes` with `threads` build
    /// threads (0: all).
    ///
    /// Embree runs a build on as many threads as the most any live device asked for
    /// (`getMaxNumThreads` in its `device.cpp`), not on the count of the device that
    /// builds: while a device of all threads lives, a one-thread device builds on all
    /// of them too.
    pub(crate) fn build(meshes: &[MeshData], threads: u32) -> Self {
        use embree3::{BufferUsage, Config, Device, Format, GeometryKind};
        let device = Device::with_config(Config {
            threads,
            ..Config::default()
        })
        .expect("an Embree device");
        let mut scene = device.create_scene().expect("an Embree scene");
        for data in meshes {
            let mut mesh = device
                .create_geometry(GeometryKind::TRIANGLE)
                .expect("an Embree triangle mesh");
            let positions: Vec<[f32; 3]> = data.positions.iter().map(|p| p.to_array()).collect();
            mesh.set_new_buffer::<[f32; 3]>(
                BufferUsage::VERTEX,
                0,
                Format::FLOAT3,
                12,
                positions.len(),
            )
            .expect("a vertex buffer")
            .copy_from_slice(&positions);
            mesh.set_new_buffer::<[u32; 3]>(
                BufferUsage::INDEX,
                0,
                Format::UINT3,
                12,
                data.triangles.len(),
            )
            .expect("an index buffer")
            .copy_from_slice(&data.triangles);
            let mesh = mesh.commit();
            scene.attach_geometry(&mesh);
        }
        scene.commit();
        Self {
            scene,
            _device: device,
        }
    }

    /// `rtcIntersect1`: the closest hit's `t`.
    pub(crate) fn closest_t(&self, ray: &Ray) -> Option<f32> {
        let mut context = embree3::IntersectContext::incoherent();
        let mut ray_hit = embree3::RayHit::from(embree3::Ray::segment(
            ray.origin.to_array(),
            ray.direction.to_array(),
            0.0,
            f32::INFINITY,
        ));
        self.scene.intersect(&mut context, &mut ray_hit);
        ray_hit.hit.is_valid().then_some(ray_hit.ray.tfar)
    }

    /// The sum of the hit distances of `rays` traced one by one (`rtcIntersect1`).
    pub(crate) fn trace_single(&self, rays: &[Ray]) -> f32 {
        rays.iter().filter_map(|ray| self.closest_t(ray)).sum()
    }

    /// The same 16 at a time (`rtcIntersect16`), in a coherent context when `rays`
    /// holds tiles of 4 x 4 pixels, else in an incoherent one. A last packet of fewer
    /// rays repeats its last ray in the missing lanes, counted once.
    pub(crate) fn trace_16(&self, rays: &[Ray], coherent: bool) -> f32 {
        let mut context = context(coherent);
        let valid = embree3::ValidMaskN::<16>::all_active();
        let mut sum = 0.0;
        for tile in rays.chunks(16) {
            let ray = |i: usize| &tile[i.min(tile.len() - 1)];
            let mut ray_hit = embree3::RayHit16 {
                ray: embree3::Ray16::new(
                    std::array::from_fn(|i| ray(i).origin.to_array()),
                    std::array::from_fn(|i| ray(i).direction.to_array()),
                ),
                hit: embree3::Hit16::new(),
            };
            self.scene.intersect16(&mut context, &mut ray_hit, &valid);
            sum += (ray_hit.ray.tfar.iter().zip(&ray_hit.hit.geomID))
                .take(tile.len())
                .filter(|&(_, &g)| g != embree3::INVALID_ID)
                .map(|(t, _)| t)
                .sum::<f32>();
        }
        sum
    }

    /// How many of `rays` hit something with `t` in `[0, t_max)`, asked one by one
    /// (`rtcOccluded1`).
    pub(crate) fn occluded_single(&self, rays: &[Ray], t_max: f32) -> f32 {
        let mut context = embree3::IntersectContext::incoherent();
        rays.iter()
            .filter(|ray| {
                let mut ray = embree3::Ray::segment(
                    ray.origin.to_array(),
                    ray.direction.to_array(),
                    0.0,
                    t_max,
                );
                self.scene.occluded(&mut context, &mut ray)
            })
            .count() as f32
    }

    /// The same 16 at a time (`rtcOccluded16`), in a coherent or an incoherent context.
    pub(crate) fn occluded_16(&self, rays: &[Ray], t_max: f32, coherent: bool) -> f32 {
        let mut context = context(coherent);
        let valid = embree3::ValidMaskN::<16>::all_active();
        let mut count = 0;
        for tile in rays.chunks(16) {
            let ray = |i: usize| &tile[i.min(tile.len() - 1)];
            let mut rays = embree3::Ray16::segment(
                std::array::from_fn(|i| ray(i).origin.to_array()),
                std::array::from_fn(|i| ray(i).direction.to_array()),
                [0.0; 16],
                [t_max; 16],
            );
            self.scene.occluded16(&mut context, &mut rays, &valid);
            count += (rays.tfar.iter().take(tile.len()))
                .filter(|&&t| t == f32::NEG_INFINITY)
                .count();
        }
        count as f32
    }
}

fn context(coherent: bool) -> embree3::IntersectContext {
    if coherent {
        embree3::IntersectContext::coherent()
    } else {
        embree3::IntersectContext::incoherent()
    }
}
