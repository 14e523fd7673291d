//! Judging a student's picture by its camera: the catalogue's label maps, made once per
//! scene, against the picture's edges.

use viewray_camera::{Mistake, Mistakes};
use viewray_compare::{
    CameraCandidates, GeometryJudgement, GeometryVerdict, LabelMap, PictureEdges, RgbaImage,
};
use viewray_render::object_labels;
use viewray_scene::Scene;

/// A scene's cameras, right and mistaken, labelled once to judge many pictures of it.
#[derive(Clone, Debug)]
pub struct PictureJudge {
    candidates: CameraCandidates,
    /// For each candidate map, the catalogue entries that make it (several when they
    /// make the same picture of this scene).
    entries: Vec<Vec<Mistake>>,
}

/// Which of the catalogue's entries explain a picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Explanation {
    /// The entries, each making the same picture of this scene: any of them is the
    /// student's mistake.
    pub mistakes: Vec<Mistake>,
    /// How well their picture agrees with the student's (1 is perfectly).
    pub agreement: f64,
}

/// The judgement of a picture's camera.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraVerdict {
    /// The right camera explains the picture's geometry.
    Right {
        /// How well (1 is perfectly).
        agreement: f64,
    },
    /// A catalogue entry explains it clearly better than the right camera.
    Mistaken {
        /// The entries.
        explanation: Explanation,
        /// How well the right camera agrees with the picture.
        right: f64,
    },
    /// Neither the right camera nor any entry explains it.
    Unexplained {
        /// How well the right camera agrees with the picture.
        right: f64,
        /// The entries that came closest, for the record.
        closest: Option<Explanation>,
    },
    /// The picture is not the reference's size.
    WrongSize {
        /// The picture's width and height.
        found: (u32, u32),
        /// The reference's.
        expected: (u32, u32),
    },
}

impl CameraVerdict {
    /// Whether the camera is right.
    pub fn passed(&self) -> bool {
        matches!(self, CameraVerdict::Right { .. })
    }
}

impl PictureJudge {
    /// Labels `scene` through its camera and through the camera of every catalogue
    /// entry that fits it, and groups the entries that make the same label map; an
    /// entry whose map is the right one (a shift left out where there is no shift) is no
    /// candidate, since no picture could tell it.
    pub fn new(scene: &Scene) -> PictureJudge {
        let camera = scene.camera();
        let right = object_labels(scene, camera);
        let mistaken: Vec<(Mistake, Vec<u32>)> = Mistake::ALL
            .into_iter()
            .filter_map(|mistake| {
                let wrong = camera.with_mistakes(Mistakes::one(mistake)).ok()?;
                Some((mistake, object_labels(scene, &wrong)))
            })
            .collect();
        let mut maps: Vec<Vec<u32>> = Vec::new();
        let mut entries: Vec<Vec<Mistake>> = Vec::new();
        for (mistake, map) in mistaken {
            if same_partition(&map, &right) {
                continue;
            }
            match maps.iter().position(|m| same_partition(m, &map)) {
                Some(k) => entries[k].push(mistake),
                None => {
                    maps.push(map);
                    entries.push(vec![mistake]);
                }
            }
        }
        let (width, height) = (camera.width(), camera.height());
        let named = entries
            .iter()
            .zip(maps)
            .map(|(group, map)| {
                let name = group
                    .iter()
                    .map(|m| m.id())
                    .collect::<Vec<_>>()
                    .join(" or ");
                let map = LabelMap::new(width, height, map).expect("a map of the camera's size");
                (name, map)
            })
            .collect();
        let right = LabelMap::new(width, height, right).expect("a map of the camera's size");
        let candidates =
            CameraCandidates::new(&right, named).expect("every map is of the camera's size");
        PictureJudge {
            candidates,
            entries,
        }
    }

    /// The size of the pictures this judge takes.
    pub fn size(&self) -> (u32, u32) {
        self.candidates.size()
    }

    /// The groups of catalogue entries this scene can tell apart, in the catalogue's
    /// order (entries that make the same picture together).
    pub fn entries(&self) -> &[Vec<Mistake>] {
        &self.entries
    }

    /// The right camera's and the catalogue's label maps, prepared.
    pub(crate) fn candidates(&self) -> &CameraCandidates {
        &self.candidates
    }

    /// Judges the camera of `picture`, a student's render of this judge's scene.
    pub fn judge(&self, picture: &RgbaImage) -> CameraVerdict {
        if picture.dimensions() != self.size() {
            return CameraVerdict::WrongSize {
                found: picture.dimensions(),
                expected: self.size(),
            };
        }
        let edges = PictureEdges::of(picture);
        let judged = self
            .candidates
            .judge_edges(&edges)
            .expect("the picture is the maps' size");
        self.verdict(&judged)
    }

    /// The verdict of the candidates' judgement of a picture of this judge's size.
    pub(crate) fn verdict(&self, judged: &GeometryJudgement) -> CameraVerdict {
        let explanation = |group: &[usize]| Explanation {
            mistakes: group
                .iter()
                .flat_map(|&k| self.entries[k].iter().copied())
                .collect(),
            agreement: group
                .first()
                .map_or(0.0, |&k| judged.candidates[k].agreement),
        };
        let closest = || {
            let best = judged
                .candidates
                .iter()
                .map(|fit| fit.agreement * fit.coverage)
                .fold(f64::NEG_INFINITY, f64::max);
            let group: Vec<usize> = (0..judged.candidates.len())
                .filter(|&k| {
                    let fit = judged.candidates[k];
                    fit.agreement * fit.coverage == best
                })
                .collect();
            (!group.is_empty()).then(|| explanation(&group))
        };
        match &judged.verdict {
            GeometryVerdict::Right => CameraVerdict::Right {
                agreement: judged.right.agreement,
            },
            GeometryVerdict::Candidate(group) => CameraVerdict::Mistaken {
                explanation: explanation(group),
                right: judged.right.agreement,
            },
            GeometryVerdict::Unexplained => CameraVerdict::Unexplained {
                right: judged.right.agreement,
                closest: closest(),
            },
        }
    }
}

/// Whether two label maps split the pixels into the same regions (whatever numbers
/// name them): then they make the same boundaries, the same picture for a judge.
fn same_partition(a: &[u32], b: &[u32]) -> bool {
    use std::collections::HashMap;
    if a.len() != b.len() {
        return false;
    }
    let (mut forward, mut backward) = (HashMap::new(), HashMap::new());
    a.iter()
        .zip(b)
        .all(|(&x, &y)| *forward.entry(x).or_insert(y) == y && *backward.entry(y).or_insert(x) == x)
}
