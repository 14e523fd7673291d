//! The render loop: tiles in parallel, samples per pixel, statistics.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};

use glam::{DVec2, Vec3};
use rayon::prelude::*;
use viewray_camera::{Camera, CameraSample};
use viewray_geometry::{DRay, ObjectHit, Ray, Reach};
use viewray_scene::{Scene, Shading};

use crate::image::{Image, PixelKind};
use crate::sampling::{PixelSeed, Strata};
use crate::shade::{
    DepthMap, DepthRange, FilmPixel, FilmPoint, LitScratch, NoRecorder, Recorder, Shader, T_MIN,
};

/// The default number of mirror bounces a ray follows.
pub const MAX_REFLECTION_DEPTH: u32 = 4;

/// The default side of a square tile, in pixels.
pub const TILE_SIZE: u32 = 16;

/// How to render: threads, tiles and bounces. The image size and samples per pixel are
/// the scene's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderSettings {
    /// How many threads to render on, in a pool of their own; `None` uses rayon's
    /// global pool (one thread per core, as does `Some(0)`). The image is the same, byte
    /// for byte, for any number.
    pub threads: Option<usize>,
    /// The side of a square tile, in pixels (0 counts as 1): the unit of parallel work
    /// and of progress.
    pub tile_size: u32,
    /// How many mirror bounces a ray follows; beyond that, a mirror reflects black.
    pub max_reflection_depth: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            threads: None,
            tile_size: TILE_SIZE,
            max_reflection_depth: MAX_REFLECTION_DEPTH,
        }
    }
}

/// What a render looks through and how: the camera (with the image size), the samples
/// per pixel and the shading. [`View::of`] takes a scene's own; a different view renders
/// the same loaded scene (its geometry, BVHs, materials and lights) through another
/// camera without building anything again, as a live viewer needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The camera, with the image size.
    pub camera: Camera,
    /// Samples per pixel; 0 counts as 1.
    pub samples: u32,
    /// How hits are coloured.
    pub shading: Shading,
}

impl View {
    /// The scene's own view: its camera, samples and shading, as [`render`] uses.
    pub fn of(scene: &Scene) -> View {
        View {
            camera: *scene.camera(),
            samples: scene.samples(),
            shading: scene.shading(),
        }
    }
}

/// What a render counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Rays traced: primary rays, shadow rays, reflected rays, and for
    /// [`Shading::Depth`] the pre-pass's one ray per pixel.
    pub rays: u64,
}

/// A finished render.
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    /// The image: colour for Flat and Lit, data for Normals and Depth (see
    /// [`PixelKind`]).
    pub image: Image,
    /// What the render counted.
    pub stats: RenderStats,
}

/// Why a render could not run.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The thread pool for [`RenderSettings::threads`] could not be started.
    #[error("cannot start {threads} render threads: {message}")]
    ThreadPool {
        /// The number of threads asked for.
        threads: usize,
        /// What went wrong.
        message: String,
    },
    /// The render was given up: its cancellation flag was set
    /// ([`render_view_cancellable`]).
    #[error("the render was cancelled")]
    Cancelled,
}

/// Renders `scene`: for each pixel, generate viewing rays, find the closest object each
/// meets, and determine its colour.
///
/// The image is split into square tiles rendered in parallel; `progress(done, total)` is
/// called (from any thread) after each tile with the number of pixels finished and the
/// image's total. Every sample's position comes from its pixel and index alone (see
/// the crate docs), so the result does not depend on `settings.threads` or on
/// scheduling.
///
/// # Errors
/// [`RenderError::ThreadPool`] if `settings.threads` asks for a pool that cannot be
/// started.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    progress: impl Fn(u64, u64) + Sync,
) -> Result<Rendered, RenderError> {
    render_view(scene, &View::of(scene), settings, progress)
}

/// Renders `scene` through `view` instead of the scene's own camera, samples and
/// shading: the same image [`render`] gives for a scene loaded with that camera, image
/// size, samples and shading, without loading or building the scene again.
///
/// # Errors
/// [`RenderError::ThreadPool`] if `settings.threads` asks for a pool that cannot be
/// started.
pub fn render_view(
    scene: &Scene,
    view: &View,
    settings: &RenderSettings,
    progress: impl Fn(u64, u64) + Sync,
) -> Result<Rendered, RenderError> {
    render_view_cancellable(scene, view, settings, progress, &AtomicBool::new(false))
}

/// [`render_view`], given up as soon as `cancelled` is set (a live viewer's render whose
/// picture nobody waits for any more): the flag is read before each tile, so a render
/// stops within a tile's work of it being set.
///
/// # Errors
/// [`RenderError::Cancelled`] if `cancelled` was set before the last tile;
/// [`RenderError::ThreadPool`] as [`render_view`].
pub fn render_view_cancellable(
    scene: &Scene,
    view: &View,
    settings: &RenderSettings,
    progress: impl Fn(u64, u64) + Sync,
    cancelled: &AtomicBool,
) -> Result<Rendered, RenderError> {
    let rendered = match settings.threads {
        None => render_on_current_pool(scene, view, settings, &progress, cancelled),
        Some(threads) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .thread_name(|i| format!("viewray-render-{i}"))
                .build()
                .map_err(|error| RenderError::ThreadPool {
                    threads,
                    message: error.to_string(),
                })?;
            pool.install(|| render_on_current_pool(scene, view, settings, &progress, cancelled))
        }
    };
    rendered.ok_or(RenderError::Cancelled)
}

/// The side of the blocks of pixels whose viewing rays are traced together, as one
/// packet of 64 rays (see [`World::closest_objects`](viewray_geometry::World::closest_objects)).
const BLOCK_SIZE: u32 = 8;
/// The most rays of a block.
const BLOCK_RAYS: usize = (BLOCK_SIZE * BLOCK_SIZE) as usize;

/// What one thread reuses from tile to tile: the pixels' sums, their differentials,
/// and a block's rays and hits.
struct TileBuffers {
    /// The tile's pixels, row by row.
    pixels: Vec<Vec3>,
    /// Each pixel's centre and ray differentials, worked out by the first sample that
    /// needs them (empty when the shading asks for no film points).
    film: Vec<FilmPixel>,
    /// Room for a block's rays, and for each the pixel it belongs to, as its index in
    /// `pixels` (its row and column follow from the tile, where a film point asks for
    /// them), and their hits: one slot per pixel of a block, filled from the front.
    /// Arrays, not vectors: with the length a constant, writing a generated ray is a
    /// store and a compare (8 instructions fewer per ray than through a slice's length).
    rays: [Ray; BLOCK_RAYS],
    ray_pixels: [u32; BLOCK_RAYS],
    hits: [Option<ObjectHit>; BLOCK_RAYS],
    /// What Lit shading reuses from block to block.
    lit: LitScratch,
    /// Each pixel's seed for its samples, block by block in the order `render` takes
    /// the blocks, each block's row by row (empty with one sample a pixel).
    seeds: Vec<PixelSeed>,
    /// A block's camera samples, row by row.
    samples: [CameraSample; BLOCK_RAYS],
    /// For each block of the tile, in the order `render` takes them, what its rays
    /// may meet ([`Shader::block_reach`]).
    reach: Vec<Reach>,
}

impl TileBuffers {
    fn new(tile_size: u32) -> Self {
        let pixels = tile_size as usize * tile_size as usize;
        Self {
            pixels: Vec::with_capacity(pixels),
            film: Vec::with_capacity(pixels),
            rays: [Ray::new(Vec3::ZERO, Vec3::ZERO); BLOCK_RAYS],
            ray_pixels: [0; BLOCK_RAYS],
            hits: [None; BLOCK_RAYS],
            lit: LitScratch::default(),
            seeds: Vec::with_capacity(pixels),
            samples: [CameraSample::CENTER; BLOCK_RAYS],
            reach: Vec::new(),
        }
    }

    /// Renders `tile` into `pixels`; returns the number of rays traced.
    ///
    /// Each sample index is traced over the whole tile, block by block, so that the
    /// viewing rays of a block of neighbouring pixels go to the geometry as one packet;
    /// each pixel still adds its samples in index order, so the sums are the same as
    /// pixel by pixel.
    fn render(&mut self, tile: &Tile, setup: &TileSetup<'_>, samples: u32) -> u64 {
        self.start(tile, setup);
        self.render_started(tile, setup, samples)
    }

    /// [`TileBuffers::render`] of a tile [`TileBuffers::start`] has set up.
    #[inline]
    fn render_started(&mut self, tile: &Tile, setup: &TileSetup<'_>, samples: u32) -> u64 {
        let mut rays = 0;
        for index in 0..samples {
            let mut first_seed = 0;
            let mut number = 0;
            for block_row in block_starts(tile.row, tile.height) {
                for block_col in block_starts(tile.col, tile.width) {
                    let block = Block {
                        tile,
                        row: block_row,
                        col: block_col,
                        index,
                        first_seed,
                    };
                    first_seed += block.pixels().0.len() * block.pixels().1.len();
                    let reach = self.reach[number];
                    rays += if reach == Reach::Nothing {
                        self.add_background(&block, setup.shader)
                    } else {
                        self.render_block(&block, setup, reach, &mut NoRecorder)
                    };
                    number += 1;
                }
            }
        }
        // The mean of each pixel's samples (one sample is its own mean: dividing by 1
        // changes no bit, and is a million divisions for a megapixel image).
        if samples > 1 {
            for pixel in &mut self.pixels {
                *pixel /= samples as f32;
            }
        }
        rays
    }

    /// Makes the pixels of `tile` black and their ray differentials unknown, works out
    /// what each block's rays may meet, and the seeds of the pixels of the blocks that
    /// trace rays if they take several samples.
    #[inline]
    fn start(&mut self, tile: &Tile, setup: &TileSetup<'_>) {
        let shader = setup.shader;
        let pixel_count = tile.width as usize * tile.height as usize;
        let seeded = setup.strata.shared_sample().is_none();
        self.seeds.clear();
        self.reach.clear();
        // Block by block as `render` takes them, each block's row by row, so that a
        // block's seeds are one slice. A block that meets nothing (a few box tests)
        // draws no samples: its seeds only hold its place.
        for block_row in block_starts(tile.row, tile.height) {
            for block_col in block_starts(tile.col, tile.width) {
                let (rows, cols) = Block::pixels_at(tile, block_row, block_col);
                let reach = shader.block_reach(rows.clone(), cols.clone());
                self.reach.push(reach);
                if !seeded {
                    continue;
                }
                for row in rows {
                    self.seeds.extend(cols.clone().map(|col| match reach {
                        Reach::Nothing => PixelSeed::default(),
                        _ => PixelSeed::new(row, col),
                    }));
                }
            }
        }
        self.pixels.clear();
        self.pixels.resize(pixel_count, Vec3::ZERO);
        // A fresh cell per pixel costs a few kilobytes of writes per tile: only for a
        // shading that may ask for film points.
        self.film.clear();
        if shader.uses_film_points() {
            for row in tile.row..tile.row + tile.height {
                let y = f64::from(row);
                self.film.extend(
                    (tile.col..tile.col + tile.width)
                        .map(|col| FilmPixel::new(DVec2::new(f64::from(col), y) + 0.5)),
                );
            }
        }
    }

    /// Adds the background to every pixel of `block`, whose rays all surely hit nothing
    /// ([`Shader::block_reach`]): what tracing them would add, in the same
    /// order, without making them; returns the number of rays they count for (the
    /// camera has one for each pixel).
    #[inline]
    fn add_background(&mut self, block: &Block<'_>, shader: &Shader<'_>) -> u64 {
        let (rows, cols) = block.pixels();
        let tile = block.tile;
        let background = shader.background();
        for row in rows.clone() {
            let start = ((row - tile.row) * tile.width + (cols.start - tile.col)) as usize;
            for pixel in &mut self.pixels[start..start + cols.len()] {
                *pixel += background;
            }
        }
        (rows.len() * cols.len()) as u64
    }

    /// Traces sample `block.index` of the block of pixels at `(block.row, block.col)`
    /// (at most [`BLOCK_SIZE`] square, inside its tile) and adds each value to its
    /// pixel; returns the number of rays traced. The rays meet only what `reach` says
    /// they may meet (see [`Shader::trace_primary_within`]). `recorder` is told the
    /// numbers of the pixel it follows, if that pixel is in the block.
    #[inline]
    fn render_block<R: Recorder>(
        &mut self,
        block: &Block<'_>,
        setup: &TileSetup<'_>,
        reach: Reach,
        recorder: &mut R,
    ) -> u64 {
        let &Block {
            tile,
            index,
            first_seed,
            ..
        } = block;
        let &TileSetup {
            shader,
            camera,
            strata,
            spacing,
        } = setup;
        // Generate the block's rays: through one sample point shared by every pixel (one
        // sample: the centre), the camera does a block at a time. Written by index with
        // the count in a local (pushes kept each vector's length in memory, stored and
        // loaded again for every ray).
        let mut count = 0;
        let (rows, cols) = block.pixels();
        let block_rays: &mut [Ray] = &mut self.rays;
        let ray_pixels: &mut [u32] = &mut self.ray_pixels;
        let take = |row: u32, col: u32, ray: Option<DRay>| {
            let pixel = (row - tile.row) * tile.width + (col - tile.col);
            match ray {
                Some(ray) => {
                    block_rays[count] = ray.as_ray();
                    ray_pixels[count] = pixel;
                    count += 1;
                }
                None => self.pixels[pixel as usize] += shader.background(),
            }
        };
        if let Some(sample) = strata.shared_sample() {
            camera.generate_block_rays(rows, cols, sample, take);
        } else {
            // Each pixel's own sample, drawn from its seed for the whole block first
            // (the block's seeds are one slice, its samples row by row); then the camera
            // works out what its rays share once, and each ray.
            let count = rows.len() * cols.len();
            let seeds = &self.seeds[first_seed..first_seed + count];
            strata.index(index).draw(seeds, &mut self.samples[..count]);
            strata.sampled_block_rays(camera, (rows, cols), &self.samples[..count], take);
        }

        if R::ACTIVE
            && let Some((row, col)) = recorder.pixel()
        {
            // The followed pixel's ray in the block, if the camera has one.
            let pixel = (row - tile.row) * tile.width + (col - tile.col);
            let position = self.ray_pixels[..count].iter().position(|&p| p == pixel);
            recorder.follow_ray(position);
        }

        // Trace them together (which writes every hit, so the buffer needs only the
        // right length) and shade them together, each sample's value added straight to
        // its pixel.
        let (block_rays, hits) = (&self.rays[..count], &mut self.hits[..count]);
        shader.trace_primary_within(reach, block_rays, hits);
        if R::ACTIVE
            && let Some(i) = recorder.followed_ray()
        {
            recorder.ray(0, &block_rays[i], T_MIN);
        }
        let (ray_pixels, film) = (&self.ray_pixels, &self.film);
        let pixels = &mut self.pixels;
        let mut rays = 0;
        shader.shade_primaries(
            block_rays,
            hits,
            |i| FilmPoint {
                pixel: &film[ray_pixels[i] as usize],
                spacing,
            },
            (&mut self.lit, recorder),
            |i, color| pixels[ray_pixels[i] as usize] += color,
            &mut rays,
        );
        rays
    }
}

/// What every tile of a render shares: the shading, the camera, where samples fall, and
/// the side of the square of film one sample stands for (`1 / sqrt(samples)` pixels).
struct TileSetup<'a> {
    shader: &'a Shader<'a>,
    camera: &'a Camera,
    strata: &'a Strata,
    spacing: f64,
}

/// A block of a tile to trace: its top-left pixel and the sample index.
struct Block<'a> {
    tile: &'a Tile,
    row: u32,
    col: u32,
    index: u32,
    /// Where the block's pixels' seeds start in the tile's.
    first_seed: usize,
}

impl Block<'_> {
    /// The rows and columns of the block.
    fn pixels(&self) -> (Range<u32>, Range<u32>) {
        Self::pixels_at(self.tile, self.row, self.col)
    }

    /// The rows and columns of the block of `tile` whose top-left pixel is `(row, col)`.
    fn pixels_at(tile: &Tile, row: u32, col: u32) -> (Range<u32>, Range<u32>) {
        (
            row..(row + BLOCK_SIZE).min(tile.row + tile.height),
            col..(col + BLOCK_SIZE).min(tile.col + tile.width),
        )
    }
}

/// A rectangle of pixels: rows `row..row + height`, columns `col..col + width`.
#[derive(Clone, Copy, Debug)]
struct Tile {
    row: u32,
    col: u32,
    width: u32,
    height: u32,
}

/// The tiles covering a `width x height` image, row by row; `size` is at least 1.
fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    (0..height.div_ceil(size))
        .flat_map(|tile_row| {
            (0..width.div_ceil(size)).map(move |tile_col| {
                let (row, col) = (tile_row * size, tile_col * size);
                Tile {
                    row,
                    col,
                    width: size.min(width - col),
                    height: size.min(height - row),
                }
            })
        })
        .collect()
}

fn render_on_current_pool(
    scene: &Scene,
    view: &View,
    settings: &RenderSettings,
    progress: &(impl Fn(u64, u64) + Sync),
    cancelled: &AtomicBool,
) -> Option<Rendered> {
    let camera = &view.camera;
    let (width, height) = (camera.width(), camera.height());
    let samples = view.samples.max(1);

    // For depth images, find the range of depths first.
    let (depth_map, rays) = depth_map(scene, view);
    let shader = Shader::new(scene, view, settings.max_reflection_depth, depth_map);
    let strata = Strata::new(samples).with_lens(view.camera.projection().has_lens());
    let setup = TileSetup {
        shader: &shader,
        camera,
        strata: &strata,
        spacing: 1.0 / f64::from(samples).sqrt(),
    };
    let total = u64::from(width) * u64::from(height);
    let done = AtomicU64::new(0);
    let traced = AtomicU64::new(0);
    let tile_size = settings.tile_size.max(1);
    let tiles = tiles(width, height, tile_size);

    // The image, as bands one tile high that tiles lock while they copy their pixels in.
    // A zeroed allocation: its pages come zeroed from the system and are first touched
    // by the tiles' copies, on every thread, instead of being filled by this one first.
    let mut pixels: Vec<Vec3> = bytemuck::zeroed_vec(width as usize * height as usize);
    let bands: Vec<Mutex<&mut [Vec3]>> = pixels
        .chunks_mut(tile_size as usize * width as usize)
        .map(Mutex::new)
        .collect();

    // Render the tiles in parallel, each thread reusing one set of tile buffers.
    tiles.par_iter().for_each_init(
        || TileBuffers::new(tile_size),
        |buffers: &mut TileBuffers, tile| {
            // A cancelled render skips its remaining tiles.
            if cancelled.load(Ordering::Relaxed) {
                return;
            }
            let rays = buffers.render(tile, &setup, samples);
            let buffer = &buffers.pixels;

            // Copy the tile into its band of the image.
            {
                let mut band = bands[(tile.row / tile_size) as usize]
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner);
                for (r, source) in buffer.chunks_exact(tile.width as usize).enumerate() {
                    let start = (tile.row % tile_size + r as u32) as usize * width as usize
                        + tile.col as usize;
                    band[start..start + tile.width as usize].copy_from_slice(source);
                }
            }
            traced.fetch_add(rays, Ordering::Relaxed);
            let pixel_count = u64::from(tile.width) * u64::from(tile.height);
            let finished = done.fetch_add(pixel_count, Ordering::Relaxed) + pixel_count;
            progress(finished, total);
        },
    );
    drop(bands);
    if cancelled.load(Ordering::Relaxed) && done.load(Ordering::Relaxed) < total {
        return None;
    }

    let kind = match view.shading {
        Shading::Flat | Shading::Lit => PixelKind::Color,
        Shading::Normals | Shading::Depth => PixelKind::Data,
    };
    Some(Rendered {
        image: Image::from_pixels(width, height, pixels, kind),
        stats: RenderStats {
            rays: rays + traced.into_inner(),
        },
    })
}

/// The Depth map of `view`, with the range of depths its image shows (found by one
/// centre ray per pixel, each block's rays traced as a packet) when it shades Depth, and
/// the number of rays that took.
fn depth_map(scene: &Scene, view: &View) -> (DepthMap, u64) {
    let camera = &view.camera;
    let (width, height) = (camera.width(), camera.height());
    let depth_map = DepthMap::new(camera);
    if view.shading != Shading::Depth {
        return (depth_map, 0);
    }
    let probe = Shader::new(scene, view, 0, depth_map);
    // One band of block rows at a time.
    let (range, rays) = (0..height.div_ceil(BLOCK_SIZE))
        .into_par_iter()
        .map(|band| {
            let mut range = DepthRange::EMPTY;
            let (mut rays, mut hits) = (Vec::new(), Vec::new());
            let mut count = 0;
            let rows = band * BLOCK_SIZE..((band + 1) * BLOCK_SIZE).min(height);
            for block_col in (0..width).step_by(BLOCK_SIZE as usize) {
                rays.clear();
                let cols = block_col..(block_col + BLOCK_SIZE).min(width);
                camera.generate_block_rays(
                    rows.clone(),
                    cols,
                    CameraSample::CENTER,
                    |_, _, ray| {
                        rays.extend(ray.map(|r| r.as_ray()));
                    },
                );
                count += rays.len() as u64;
                hits.clear();
                hits.resize(rays.len(), None);
                probe.trace_primary(&rays, &mut hits);
                for (ray, hit) in rays.iter().zip(&hits) {
                    probe.depth_probe(ray, hit.as_ref(), &mut range);
                }
            }
            (range, count)
        })
        .reduce(
            || (DepthRange::EMPTY, 0),
            |(a, ra), (b, rb)| (a.union(b), ra + rb),
        );
    (depth_map.with_range(range), rays)
}

/// Traces pixel `(row, col)` of `view`'s one-sample image as [`render_view`] renders it,
/// telling `recorder` its numbers, and returns the pixel's value: the same bits the
/// image holds. The pixel must be in the image.
///
/// `start(recorder, ray, background)` is called first with the pixel's viewing ray, as
/// the camera generates it for the pixel alone (the same bits as in its block: see
/// [`Camera::generate_block_rays`]), and the value of a pixel that sees nothing.
pub(crate) fn trace_pixel_with<R: Recorder>(
    scene: &Scene,
    view: &View,
    settings: &RenderSettings,
    (row, col): (u32, u32),
    (recorder, start): (&mut R, impl FnOnce(&mut R, Option<DRay>, Vec3)),
) -> Vec3 {
    let view = View {
        samples: 1,
        ..*view
    };
    let camera = &view.camera;
    let (depth_map, _) = depth_map(scene, &view);
    let shader = Shader::new(scene, &view, settings.max_reflection_depth, depth_map);
    let strata = Strata::new(1).with_lens(camera.projection().has_lens());
    // One sample is shared by every pixel. (Not `camera_sample`: a second caller, cold as
    // it is, stops the compiler inlining it into the render loop.)
    let sample = strata.shared_sample().unwrap_or_default();
    let ray = camera.generate_ray(row, col, sample);
    start(recorder, ray, shader.background());
    let setup = TileSetup {
        shader: &shader,
        camera,
        strata: &strata,
        spacing: 1.0,
    };
    // The tile that holds the pixel, and its block, as the render splits the image.
    let size = settings.tile_size.max(1);
    let tile = tiles(camera.width(), camera.height(), size)
        .into_iter()
        .find(|t| {
            (t.row..t.row + t.height).contains(&row) && (t.col..t.col + t.width).contains(&col)
        })
        .expect("the tiles cover the image, and the pixel is in it");
    let start_of = |start, len, at| {
        block_starts(start, len)
            .take_while(|&s| s <= at)
            .last()
            .unwrap_or(start)
    };
    let block = Block {
        tile: &tile,
        row: start_of(tile.row, tile.height, row),
        col: start_of(tile.col, tile.width, col),
        index: 0,
        first_seed: 0,
    };
    let mut buffers = TileBuffers::new(size);
    buffers.start(&tile, &setup);
    buffers.render_block(&block, &setup, Reach::Anything, recorder);
    buffers.pixels[((row - tile.row) * tile.width + (col - tile.col)) as usize]
}

/// Where the blocks of a tile's rows (or columns) `start..start + len` start.
#[inline]
fn block_starts(start: u32, len: u32) -> std::iter::StepBy<std::ops::Range<u32>> {
    (start..start + len).step_by(BLOCK_SIZE as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spheres on the ground of the animation demos through their thin lens and
    /// through a pinhole looking a little down: sky, open ground and objects.
    fn lens_and_pinhole_views(scene: &Scene) -> [View; 2] {
        let lens = View::of(scene);
        let frame = viewray_camera::Frame::from_eye_view_up(
            glam::DVec3::new(0.0, 0.6, 0.0),
            glam::DVec3::new(0.0, -0.1, -1.0),
            glam::DVec3::Y,
        )
        .unwrap();
        let projection = viewray_camera::Projection::Perspective(viewray_camera::Perspective {
            distance: 1.0,
            viewport: DVec2::new(1.2, 0.9),
            shift: DVec2::ZERO,
        });
        let pinhole = Camera::new(frame, projection, 48, 36).unwrap();
        [
            lens,
            View {
                camera: pinhole,
                ..lens
            },
        ]
    }

    #[test]
    fn blocks_that_meet_nothing_or_planes_render_as_traced() {
        let scene = viewray_scene::SceneLoader::text(
            include_str!("../../viewray-animation/scenes/spheres.ron"),
            std::path::Path::new("spheres.ron"),
        )
        .load()
        .unwrap()
        .scene;
        for view in lens_and_pinhole_views(&scene) {
            let view = View {
                camera: view.camera.with_image_size(48, 36).unwrap(),
                samples: 4,
                ..view
            };
            let shader = Shader::new(
                &scene,
                &view,
                MAX_REFLECTION_DEPTH,
                DepthMap::new(&view.camera),
            );
            let strata = Strata::new(4).with_lens(view.camera.projection().has_lens());
            let setup = TileSetup {
                shader: &shader,
                camera: &view.camera,
                strata: &strata,
                spacing: 0.5,
            };
            let tile = Tile {
                row: 0,
                col: 0,
                width: 48,
                height: 36,
            };
            let mut decided = TileBuffers::new(48);
            let decided_rays = decided.render(&tile, &setup, 4);
            // Every kind of block is there: the sky, the open ground, a sphere alone on
            // it, and more than one object.
            let kinds: [fn(&Reach) -> bool; 4] = [
                |r| *r == Reach::Nothing,
                |r| *r == Reach::Planes,
                |r| matches!(r, Reach::One(_)),
                |r| *r == Reach::Anything,
            ];
            for kind in kinds {
                assert!(decided.reach.iter().any(kind), "{:?}", decided.reach);
            }
            let mut traced = TileBuffers::new(48);
            traced.start(&tile, &setup);
            traced.reach.fill(Reach::Anything);
            let traced_rays = traced.render_started(&tile, &setup, 4);
            assert_eq!(decided_rays, traced_rays);
            let bits = |pixels: &[Vec3]| -> Vec<[u32; 3]> {
                pixels
                    .iter()
                    .map(|p| p.to_array().map(f32::to_bits))
                    .collect()
            };
            assert_eq!(bits(&decided.pixels), bits(&traced.pixels));
        }
    }

    #[test]
    fn tiles_cover_the_image_once() {
        for (width, height, size) in [(1, 1, 16), (33, 17, 16), (64, 32, 16), (5, 9, 1)] {
            let mut covered = vec![0; width as usize * height as usize];
            for tile in tiles(width, height, size) {
                assert!(tile.width >= 1 && tile.width <= size);
                for row in tile.row..tile.row + tile.height {
                    for col in tile.col..tile.col + tile.width {
                        covered[(row * width + col) as usize] += 1;
                    }
                }
            }
            assert!(
                covered.iter().all(|&c| c == 1),
                "{width} x {height} / {size}"
            );
        }
    }
}
