//! Judging a picture's geometry, whatever its shading: do its edges fall where a camera's
//! label map says objects meet?
//!
//! A student's ray tracer shades as it likes (its lights, its gamma, its brightness, its
//! samples), so its picture cannot be compared with the reference pixel by pixel. What
//! its camera decides is where each object shows: the silhouettes and occlusion edges.
//! The caller (who knows the scene) gives label maps, what each pixel's centre ray meets
//! for the right camera and for candidate wrong ones (the catalogue's mistakes), and this
//! module measures how well each explains the student's picture:
//!
//! - the picture is made blind to shading level: each channel is replaced by its rank
//!   in the picture (its share of darker pixels), which any brightening, darkening or
//!   gamma leaves as it is;
//! - the contrast of each pair of neighbouring pixels (right and down) is the summed
//!   difference of their ranks;
//! - a label map splits the pairs into boundary pairs (labels differ) and inner pairs;
//!   its **agreement** is the chance that a boundary pair has more contrast than an
//!   inner pair (the area under the ROC curve: 1 when every edge of the picture is on a
//!   boundary, 1/2 when the boundaries are no better than anywhere else);
//! - its **coverage** is the share of the picture's strong edges (pairs of contrast
//!   [`STRONG_EDGE`] or more) that lie on or next to one of its boundaries: a map that
//!   explains only some of the picture (a horizon, where the picture also shows objects)
//!   has a high agreement but a low coverage, and is no explanation.
//!
//! Shading edges (shadows, highlights, creases) lower every candidate's agreement alike;
//! a camera that puts the boundaries elsewhere lowers its own. A map with no boundary at
//! all (a picture of one colour, or nothing in view) agrees as much as the picture is
//! flat: the share of its pairs with no contrast.

use std::sync::OnceLock;

use image::RgbaImage;

use crate::chamfer;

/// What each pixel of an image sees, as labels: equal labels for the same surface.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LabelMap {
    width: u32,
    height: u32,
    labels: Vec<u32>,
}

impl LabelMap {
    /// A label map of `width x height` pixels, row by row; `None` unless `labels` holds
    /// exactly that many.
    pub fn new(width: u32, height: u32, labels: Vec<u32>) -> Option<LabelMap> {
        (labels.len() == width as usize * height as usize).then_some(LabelMap {
            width,
            height,
            labels,
        })
    }

    /// The map's width and height.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The pairs whose labels differ (see [`pair_index`]).
    fn boundaries(&self) -> Vec<u32> {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut pairs = Vec::new();
        for row in 0..h {
            for col in 0..w {
                let p = row * w + col;
                if col + 1 < w && self.labels[p] != self.labels[p + 1] {
                    pairs.push(pair_index(p, Direction::Right));
                }
                if row + 1 < h && self.labels[p] != self.labels[p + w] {
                    pairs.push(pair_index(p, Direction::Down));
                }
            }
        }
        pairs
    }
}

/// Which neighbour a pair joins a pixel to.
#[derive(Clone, Copy)]
enum Direction {
    Right,
    Down,
}

/// Pair `2p` joins pixel `p` to its right neighbour, pair `2p + 1` to the one below.
fn pair_index(pixel: usize, direction: Direction) -> u32 {
    let index = 2 * pixel
        + match direction {
            Direction::Right => 0,
            Direction::Down => 1,
        };
    u32::try_from(index).expect("images have fewer than 2^31 pixels")
}

/// The right camera's label map and the candidates', prepared once (their boundary
/// pairs) to judge many pictures against.
#[derive(Clone, Debug)]
pub struct CameraCandidates {
    width: u32,
    height: u32,
    right: Boundary,
    names: Vec<String>,
    candidates: Vec<Boundary>,
}

/// A label map's boundary: its boundary pairs, and the pixels on or next to them.
#[derive(Clone, Debug)]
struct Boundary {
    pairs: Vec<u32>,
    on: Vec<bool>,
    near: Vec<bool>,
}

impl Boundary {
    fn of(map: &LabelMap) -> Boundary {
        let pairs = map.boundaries();
        let (w, h) = (map.width as usize, map.height as usize);
        let mut on = vec![false; w * h];
        for &pair in &pairs {
            let (p, q) = pair_pixels(pair as usize, w);
            on[p] = true;
            on[q] = true;
        }
        // On a boundary, or one of its four neighbours is.
        let near = (0..w * h)
            .map(|p| {
                let (row, col) = (p / w, p % w);
                on[p]
                    || (col > 0 && on[p - 1])
                    || (col + 1 < w && on[p + 1])
                    || (row > 0 && on[p - w])
                    || (row + 1 < h && on[p + w])
            })
            .collect();
        Boundary { pairs, on, near }
    }
}

/// The two pixels of pair `pair` (see [`pair_index`]) in an image `width` wide.
fn pair_pixels(pair: usize, width: usize) -> (usize, usize) {
    let p = pair / 2;
    (
        p,
        if pair.is_multiple_of(2) {
            p + 1
        } else {
            p + width
        },
    )
}

/// How a picture's geometry was judged.
#[derive(Clone, Debug, PartialEq)]
pub struct GeometryJudgement {
    /// How well the right camera's map explains the picture.
    pub right: Fit,
    /// How well each candidate's map does, in the order given.
    pub candidates: Vec<Fit>,
    /// The verdict those numbers give.
    pub verdict: GeometryVerdict,
    /// The best coverage of any map judged, which each fit's relative coverage is of.
    pub most_coverage: f64,
}

/// How well a label map explains a picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The chance that a boundary pair has more contrast than an inner pair.
    pub agreement: f64,
    /// The share of the picture's strong edges on or next to a boundary (1 when the
    /// picture has none).
    pub coverage: f64,
    /// The two together, what the maps are ranked by: the harmonic mean of the
    /// agreement and the coverage relative to the best coverage of any map given (1
    /// when the map's boundaries are all on edges and it covers as much as any map);
    /// 0 for a map that does not explain the picture at all (see [`Fit::explains`]).
    pub score: f64,
}

impl Fit {
    /// Whether the map explains the picture at all: its boundaries are where the
    /// contrast is ([`AGREEMENT_NEEDED`]), and it covers at least [`COVERAGE_NEEDED`] of
    /// what the best-covering map covers (the rest of a picture's edges may be shadows,
    /// highlights and creases, which no map holds).
    pub fn explains(&self) -> bool {
        self.score > 0.0
    }

    fn new(agreement: f64, coverage: f64, most: f64) -> Fit {
        let relative = if most > 0.0 { coverage / most } else { 1.0 };
        let explains = agreement >= AGREEMENT_NEEDED && relative >= COVERAGE_NEEDED;
        let score = if explains {
            2.0 * agreement * relative / (agreement + relative)
        } else {
            0.0
        };
        Fit {
            agreement,
            coverage,
            score,
        }
    }
}

/// The verdict of [`CameraCandidates::judge`].
#[derive(Clone, Debug, PartialEq)]
pub enum GeometryVerdict {
    /// The right camera explains the picture as well as any candidate, and well.
    Right,
    /// Candidates explain the picture clearly better than the right camera (a higher
    /// score by [`CANDIDATE_MARGIN`], a higher agreement by [`AGREEMENT_MARGIN`]): these
    /// (indices into the candidates; several when their maps agree equally well).
    Candidate(Vec<usize>),
    /// Nothing explains the picture well: neither the right camera nor a candidate.
    Unexplained,
}

/// The agreement the explanation of a picture must reach: below it, the picture's
/// edges are not where any camera given puts them.
pub const AGREEMENT_NEEDED: f64 = 0.80;
/// The coverage the explanation of a picture must reach, as a share of the best
/// coverage of any map given (see [`Fit::explains`]).
pub const COVERAGE_NEEDED: f64 = 0.5;
/// The contrast (of 765: three channels of ranks) from which a pair is a strong edge.
pub const STRONG_EDGE: u16 = 96;
/// How much better (in [`Fit::score`]) than the right camera a candidate must explain a
/// picture to be named; scores tied within this are the right camera's.
pub const CANDIDATE_MARGIN: f64 = 0.01;
/// How much higher than the right camera's a candidate's agreement must be for it to be
/// named, besides its score: a candidate whose boundaries sit no better on the picture's
/// edges than the right camera's is not convicted by coverage alone. The coverage of maps
/// a pixel apart (the half-pixel mistakes) differs by the chance of shading edges near
/// their boundaries, and ranks bias an antialiased edge's contrast towards the side of the
/// larger region, so a right, antialiased picture can seem half a pixel off by a hair:
/// on viewray's own 4-sample render of its cavalier fixture the right camera agrees
/// 0.912 and the pixel-corner one 0.920 (their scores 0.937 and 0.955). The smallest gap
/// of a real mistake in the planted matrix (`judge_matrix`) is pixel-one-based on its
/// canonical camera, 0.921 against the right camera's 0.897.
pub const AGREEMENT_MARGIN: f64 = 0.015;
/// Candidates whose scores lie within this of the best are named together.
const TIE: f64 = 1e-3;

impl CameraCandidates {
    /// Prepares the right camera's map and the candidates' (each with a name the caller
    /// chooses, such as a catalogue id).
    ///
    /// # Errors
    /// The name of the first candidate whose map is not the right map's size.
    pub fn new(right: &LabelMap, candidates: Vec<(String, LabelMap)>) -> Result<Self, String> {
        let (names, maps): (Vec<String>, Vec<LabelMap>) = candidates.into_iter().unzip();
        if let Some(k) = maps.iter().position(|m| m.size() != right.size()) {
            return Err(names[k].clone());
        }
        Ok(CameraCandidates {
            width: right.width,
            height: right.height,
            right: Boundary::of(right),
            names,
            candidates: maps.iter().map(Boundary::of).collect(),
        })
    }

    /// The image size the maps are for.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The candidates' names, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Judges `picture` (of the maps' size; `None` otherwise): how well the right camera
    /// and each candidate explain its edges, and the verdict.
    pub fn judge(&self, picture: &RgbaImage) -> Option<GeometryJudgement> {
        if picture.dimensions() != (self.width, self.height) {
            return None;
        }
        self.judge_edges(&PictureEdges::of(picture))
    }

    /// [`CameraCandidates::judge`] of a picture whose edges are measured already (of the
    /// maps' size; `None` otherwise).
    pub fn judge_edges(&self, edges: &PictureEdges) -> Option<GeometryJudgement> {
        if edges.size != (self.width, self.height) {
            return None;
        }
        let contrast = &edges.contrast;
        let measured: Vec<(f64, f64)> = std::iter::once(&self.right)
            .chain(&self.candidates)
            .map(|boundary| contrast.measure(boundary))
            .collect();
        let most = measured.iter().map(|m| m.1).fold(0.0, f64::max);
        let mut fits = measured
            .iter()
            .map(|&(agreement, coverage)| Fit::new(agreement, coverage, most));
        let right = fits.next().expect("the right map is measured first");
        let candidates: Vec<Fit> = fits.collect();
        // Only candidates that agree clearly better than the right camera may be named.
        let clear = |fit: &Fit| fit.agreement > right.agreement + AGREEMENT_MARGIN;
        let best = candidates
            .iter()
            .filter(|fit| clear(fit))
            .map(|fit| fit.score)
            .fold(0.0, f64::max);
        let verdict = if best > 0.0 && best > right.score + CANDIDATE_MARGIN {
            GeometryVerdict::Candidate(
                (0..candidates.len())
                    .filter(|&k| clear(&candidates[k]) && candidates[k].score >= best - TIE)
                    .collect(),
            )
        } else if right.explains() {
            GeometryVerdict::Right
        } else {
            GeometryVerdict::Unexplained
        };
        Some(GeometryJudgement {
            right,
            candidates,
            verdict,
            most_coverage: most,
        })
    }

    /// How well `map`, a camera the caller made besides the candidates (an eye moved), explains
    /// the picture whose edges are `edges`, in the terms of `judged` (its judgement by
    /// these maps): `None` when the sizes differ.
    pub fn fit_other(
        &self,
        edges: &PictureEdges,
        judged: &GeometryJudgement,
        map: &LabelMap,
    ) -> Option<Fit> {
        if edges.size != (self.width, self.height) || map.size() != edges.size {
            return None;
        }
        let (agreement, coverage) = edges.contrast.measure(&Boundary::of(map));
        Some(Fit::new(
            agreement,
            coverage,
            judged.most_coverage.max(coverage),
        ))
    }

    /// For each pixel (row by row), whether it lies more than `margin` pixels away from
    /// every pixel on or next to the right map's boundaries: inside one surface.
    pub fn interior(&self, margin: usize) -> Vec<bool> {
        let (w, h) = (self.width as usize, self.height as usize);
        let near = &self.right.near;
        // Grown by `margin` along rows, then along columns.
        let mut rows = vec![false; w * h];
        for row in 0..h {
            for col in 0..w {
                let (lo, hi) = (col.saturating_sub(margin), (col + margin).min(w - 1));
                rows[row * w + col] = (lo..=hi).any(|c| near[row * w + c]);
            }
        }
        let mut inside = vec![true; w * h];
        for row in 0..h {
            let (lo, hi) = (row.saturating_sub(margin), (row + margin).min(h - 1));
            for col in 0..w {
                inside[row * w + col] = !(lo..=hi).any(|r| rows[r * w + col]);
            }
        }
        inside
    }
}

/// A picture's edges, measured once (its neighbour contrasts, blind to its shading level)
/// to judge many label maps against.
pub struct PictureEdges {
    size: (u32, u32),
    contrast: Contrast,
    /// The pixels on a strong edge, and the distance from each pixel to the nearest of
    /// them, measured when a search first asks for them.
    distances: OnceLock<(Vec<bool>, Vec<u16>)>,
}

impl PictureEdges {
    /// Measures `picture`'s edges.
    pub fn of(picture: &RgbaImage) -> PictureEdges {
        PictureEdges {
            size: picture.dimensions(),
            contrast: Contrast::of(picture),
            distances: OnceLock::new(),
        }
    }

    /// How far apart `map`'s boundaries and the picture's strong edges lie: the mean
    /// distance, in pixels, from each boundary pixel to the nearest edge pixel and from
    /// each edge pixel to the nearest boundary pixel, averaged, each distance capped at
    /// 16 pixels. 0 when they coincide; unlike the
    /// agreement, it falls steadily as the boundaries approach the edges, which is what
    /// a search for a camera (a moved eye) needs. `None` when the sizes differ.
    pub fn distance(&self, map: &LabelMap) -> Option<f64> {
        if map.size() != self.size {
            return None;
        }
        let (w, h) = (self.size.0 as usize, self.size.1 as usize);
        let (strong, to_edges) = self.distances.get_or_init(|| {
            let strong = self.contrast.strong_pixels();
            let to_edges = chamfer::distances(&strong, w, h);
            (strong, to_edges)
        });
        let boundary = Boundary::of(map);
        let to_boundary = chamfer::distances(&boundary.on, w, h);
        Some(
            0.5 * (chamfer::mean_distance(to_edges, &boundary.on)
                + chamfer::mean_distance(&to_boundary, strong)),
        )
    }
}

/// The levels a pair's contrast is counted in: three channels of ranks 0..=255.
const LEVELS: usize = 3 * 255 + 1;

/// A picture's neighbour contrasts, blind to its shading level.
struct Contrast {
    width: usize,
    /// Each pair's contrast (see [`pair_index`]); pairs off the image's edge are 0.
    pairs: Vec<u16>,
    /// How many real pairs have each contrast.
    histogram: Vec<u64>,
    /// The pairs of contrast [`STRONG_EDGE`] or more.
    strong: Vec<u32>,
}

impl Contrast {
    fn of(picture: &RgbaImage) -> Contrast {
        let (w, h) = (picture.width() as usize, picture.height() as usize);
        let ranked = ranks(picture);
        let difference = |a: usize, b: usize| -> u16 {
            (0..3)
                .map(|c| u16::from(ranked[3 * a + c].abs_diff(ranked[3 * b + c])))
                .sum()
        };
        let mut pairs = vec![0_u16; 2 * w * h];
        let mut histogram = vec![0_u64; LEVELS];
        let mut strong = Vec::new();
        for row in 0..h {
            for col in 0..w {
                let p = row * w + col;
                for (direction, q, real) in [
                    (Direction::Right, p + 1, col + 1 < w),
                    (Direction::Down, p + w, row + 1 < h),
                ] {
                    if !real {
                        continue;
                    }
                    let g = difference(p, q);
                    let pair = pair_index(p, direction);
                    pairs[pair as usize] = g;
                    histogram[usize::from(g)] += 1;
                    if g >= STRONG_EDGE {
                        strong.push(pair);
                    }
                }
            }
        }
        Contrast {
            width: w,
            pairs,
            histogram,
            strong,
        }
    }

    /// The pixels on a strong edge (either pixel of a strong pair), row by row.
    fn strong_pixels(&self) -> Vec<bool> {
        let mut on = vec![false; self.pairs.len() / 2];
        for &pair in &self.strong {
            let (p, q) = pair_pixels(pair as usize, self.width);
            on[p] = true;
            on[q] = true;
        }
        on
    }

    /// A map's agreement and coverage with the picture.
    fn measure(&self, boundary: &Boundary) -> (f64, f64) {
        (
            self.agreement(&boundary.pairs),
            self.coverage(&boundary.near),
        )
    }

    /// The share of the strong edges with a pixel on or next to the boundary.
    fn coverage(&self, near: &[bool]) -> f64 {
        if self.strong.is_empty() {
            return 1.0;
        }
        let covered = self
            .strong
            .iter()
            .filter(|&&pair| {
                let (p, q) = pair_pixels(pair as usize, self.width);
                near[p] || near[q]
            })
            .count();
        count(covered as u64) / count(self.strong.len() as u64)
    }

    /// The chance that a pair of `boundary` has more contrast than one off it (ties
    /// count half); for no boundary, the share of pairs with no contrast.
    fn agreement(&self, boundary: &[u32]) -> f64 {
        let total: u64 = self.histogram.iter().sum();
        if boundary.is_empty() || total == 0 {
            return if total == 0 {
                1.0
            } else {
                count(self.histogram[0]) / count(total)
            };
        }
        let mut on = vec![0_u64; LEVELS];
        for &pair in boundary {
            on[usize::from(self.pairs[pair as usize])] += 1;
        }
        let on_total = boundary.len() as u64;
        let off_total = total - on_total;
        if off_total == 0 {
            return 1.0;
        }
        // Sum over levels: boundary pairs at this level beat the inner pairs below it
        // and tie with those at it.
        let mut below = 0_u64;
        let mut wins = 0.0;
        for (level, &n_on) in on.iter().enumerate() {
            let n_off = self.histogram[level] - n_on;
            wins += count(n_on) * (count(below) + 0.5 * count(n_off));
            below += n_off;
        }
        wins / (count(on_total) * count(off_total))
    }
}

/// A count as a float (exact below 2^53).
#[allow(clippy::cast_precision_loss)]
pub(crate) fn count(n: u64) -> f64 {
    n as f64
}

/// Each channel of each pixel replaced by its rank in the picture, 0..=255: the middle
/// of its share of darker-or-equal values. Any increasing change of a channel (gamma,
/// brightness, contrast) leaves the ranks as they are.
fn ranks(picture: &RgbaImage) -> Vec<u8> {
    let n = (picture.width() as usize * picture.height() as usize).max(1);
    let mut histograms = [[0_usize; 256]; 3];
    for pixel in picture.pixels() {
        for c in 0..3 {
            histograms[c][usize::from(pixel[c])] += 1;
        }
    }
    let tables: Vec<[u8; 256]> = histograms
        .iter()
        .map(|histogram| {
            let mut table = [0_u8; 256];
            let mut below = 0;
            for (value, &here) in histogram.iter().enumerate() {
                // (below + here / 2) / n, scaled to 0..=255 and rounded.
                let rank = (510 * below + 255 * here + n) / (2 * n);
                table[value] = u8::try_from(rank.min(255)).unwrap_or(255);
                below += here;
            }
            table
        })
        .collect();
    let mut ranked = Vec::with_capacity(3 * n);
    for pixel in picture.pixels() {
        for c in 0..3 {
            ranked.push(tables[c][usize::from(pixel[c])]);
        }
    }
    ranked
}

#[cfg(test)]
mod tests {
    use image::Rgba;

    use super::*;

    /// How a test picture colours the pixel (x, y), inside the square or not.
    type Shade = dyn Fn(u32, u32, bool) -> [u8; 3];

    /// A picture of a `size x size` square at (x0, y0) on a background, each region
    /// filled by `shade(x, y, inside)`.
    fn picture(
        (w, h): (u32, u32),
        (x0, y0, size): (u32, u32, u32),
        shade: impl Fn(u32, u32, bool) -> [u8; 3],
    ) -> RgbaImage {
        RgbaImage::from_fn(w, h, |x, y| {
            let inside = (x0..x0 + size).contains(&x) && (y0..y0 + size).contains(&y);
            let [r, g, b] = shade(x, y, inside);
            Rgba([r, g, b, 255])
        })
    }

    fn labels((w, h): (u32, u32), (x0, y0, size): (u32, u32, u32)) -> LabelMap {
        let labels = (0..h)
            .flat_map(|y| {
                (0..w).map(move |x| {
                    u32::from((x0..x0 + size).contains(&x) && (y0..y0 + size).contains(&y))
                })
            })
            .collect();
        LabelMap::new(w, h, labels).unwrap()
    }

    #[test]
    fn the_right_map_wins_whatever_the_shading() {
        let size = (40, 30);
        let square = (10, 8, 12);
        let right = labels(size, square);
        let moved = labels(size, (13, 8, 12));
        let candidates = CameraCandidates::new(&right, vec![("moved".to_owned(), moved)]).unwrap();
        // Flat colours, a gradient inside and out, and a dark gamma: the same edges.
        let shadings: [Box<Shade>; 3] = [
            Box::new(|_, _, inside| if inside { [200, 40, 40] } else { [20, 20, 60] }),
            Box::new(|x, y, inside| {
                let g = u8::try_from(x + y).unwrap();
                if inside {
                    [150 + g, 60, 40]
                } else {
                    [g, g, 90]
                }
            }),
            Box::new(|_, _, inside| if inside { [90, 3, 3] } else { [1, 1, 9] }),
        ];
        for shade in shadings {
            let judged = candidates.judge(&picture(size, square, shade)).unwrap();
            assert_eq!(judged.verdict, GeometryVerdict::Right, "{judged:?}");
            assert!(judged.right.agreement > 0.99, "{judged:?}");
            assert!(judged.right.coverage > 0.99, "{judged:?}");
            assert!(
                judged.candidates[0].agreement < judged.right.agreement - 0.1,
                "{judged:?}"
            );
        }
    }

    #[test]
    fn a_candidate_that_explains_better_is_named_with_its_ties() {
        let size = (40, 30);
        let right = labels(size, (10, 8, 12));
        let moved = labels(size, (13, 8, 12));
        let again = moved.clone();
        let candidates = CameraCandidates::new(
            &right,
            vec![
                ("moved".to_owned(), moved),
                ("same".to_owned(), again),
                ("elsewhere".to_owned(), labels(size, (25, 15, 5))),
            ],
        )
        .unwrap();
        let student = picture(size, (13, 8, 12), |_, _, inside| {
            if inside { [255, 255, 0] } else { [0, 0, 0] }
        });
        let judged = candidates.judge(&student).unwrap();
        assert_eq!(judged.verdict, GeometryVerdict::Candidate(vec![0, 1]));
        assert_eq!(candidates.names()[0], "moved");
    }

    #[test]
    fn nothing_explains_a_picture_of_other_edges() {
        let size = (40, 30);
        let right = labels(size, (10, 8, 12));
        let candidates =
            CameraCandidates::new(&right, vec![("small".to_owned(), labels(size, (2, 2, 3)))])
                .unwrap();
        let student = picture(size, (24, 14, 9), |_, _, inside| {
            if inside { [255, 255, 255] } else { [0, 0, 0] }
        });
        let judged = candidates.judge(&student).unwrap();
        assert_eq!(judged.verdict, GeometryVerdict::Unexplained, "{judged:?}");
    }

    #[test]
    fn a_flat_picture_is_explained_by_a_map_without_boundaries() {
        let size = (20, 10);
        let right = labels(size, (5, 2, 4));
        let flat = LabelMap::new(20, 10, vec![7; 200]).unwrap();
        let candidates = CameraCandidates::new(&right, vec![("flat".to_owned(), flat)]).unwrap();
        let student = picture(size, (0, 0, 0), |_, _, _| [12, 34, 56]);
        let judged = candidates.judge(&student).unwrap();
        assert_eq!(
            judged.candidates,
            vec![Fit {
                agreement: 1.0,
                coverage: 1.0,
                score: 1.0
            }]
        );
        assert!((judged.right.agreement - 0.5).abs() < 1e-12, "{judged:?}");
        assert_eq!(judged.verdict, GeometryVerdict::Candidate(vec![0]));
    }

    #[test]
    fn sizes_must_agree() {
        let right = labels((10, 10), (2, 2, 3));
        assert_eq!(
            CameraCandidates::new(
                &right,
                vec![("wide".to_owned(), labels((11, 10), (2, 2, 3)))]
            )
            .unwrap_err(),
            "wide"
        );
        let candidates = CameraCandidates::new(&right, Vec::new()).unwrap();
        assert_eq!(candidates.judge(&RgbaImage::new(10, 9)), None);
        assert_eq!(LabelMap::new(3, 3, vec![0; 8]), None);
    }

    #[test]
    fn ranks_ignore_any_increasing_change() {
        // Levels far enough apart that a gamma of 2.2 keeps them apart in 8 bits.
        let level = |k: u32| u8::try_from(20 + 25 * (k % 10)).unwrap();
        let base = picture((16, 16), (4, 4, 6), |x, y, inside| {
            if inside {
                [level(x), level(y + 3), 30]
            } else {
                [level(x + y), 10, 200]
            }
        });
        let gamma = RgbaImage::from_fn(16, 16, |x, y| {
            let p = base.get_pixel(x, y);
            let f = |c: u8| {
                let encoded = (255.0 * (f64::from(c) / 255.0).powf(2.2)).round();
                u8::try_from(encoded as i64).unwrap()
            };
            Rgba([f(p[0]), f(p[1]), f(p[2]), 255])
        });
        assert_ne!(base, gamma);
        assert_eq!(ranks(&base), ranks(&gamma));
        // Ranks span the range: the darkest value is near 0, the brightest near 255.
        let ranked = ranks(&base);
        assert!(ranked.iter().copied().min().unwrap() < 20);
        assert!(ranked.iter().copied().max().unwrap() > 235);
    }
}
