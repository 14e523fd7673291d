//! A Lit surface's lines: its material, each light with its shadow ray and Blinn-Phong
//! terms (with the surface's own numbers in the formulas).

use viewray_render::{BlinnPhong, LightSource, LightTerms, LitSurface};

use super::text::{Text, n, v3};

impl Text {
    pub(super) fn surface(&mut self, item: u32, surface: &LitSurface) {
        self.line(
            item,
            format!(
                "material {}: color {}, specular {}, shininess {}, mirror {}",
                surface.material,
                v3(surface.color),
                v3(surface.specular),
                n(surface.shininess),
                n(surface.mirror)
            ),
        );
        if let Some(grid) = &surface.grid {
            self.grid(item, grid);
        }
        self.line(
            item,
            format!(
                "v = -direction/|direction| = {}   (toward the eye)",
                v3(surface.view)
            ),
        );
        self.line(
            item,
            format!(
                "shadow and mirror rays start at {}   (p moved off the surface along its normal)",
                v3(surface.origin)
            ),
        );
    }

    pub(super) fn light(&mut self, item: u32, terms_bounce: u32, terms: &LightTerms) {
        let (source, l_rule) = match terms.source {
            LightSource::Point(position) => (
                format!("point at {}", v3(position)),
                "(light - start)/|light - start|",
            ),
            LightSource::Directional(direction) => {
                (format!("directional along {}", v3(direction)), "-direction")
            }
        };
        self.line(
            item,
            format!(
                "light {}, {source}, I = {}:",
                terms.light,
                v3(terms.intensity)
            ),
        );
        let sub = item + 1;
        let r2 = match terms.source {
            LightSource::Point(_) => format!(", r^2 = {}", n(terms.distance_squared)),
            LightSource::Directional(_) => String::new(),
        };
        self.line(sub, format!("l = {l_rule} = {}{r2}", v3(terms.l)));
        let Some(shadow) = terms.shadow else {
            self.line(
                sub,
                "the light is behind the surface (n.l <= 0): no shadow ray, nothing added",
            );
            self.line(item, format!("colour so far {}", v3(terms.color)));
            return;
        };
        let verdict = match (shadow.blocked, shadow.blocker) {
            (false, _) => "not blocked".to_owned(),
            (true, Some((object, shape, t))) => format!(
                "blocked by object {object} ({}) at t = {}: nothing added",
                shape.name(),
                n(t)
            ),
            (true, None) => "blocked: nothing added".to_owned(),
        };
        let range = if shadow.t_max.is_finite() {
            format!("{} <= t < {}", n(shadow.t_min), n(shadow.t_max))
        } else {
            format!("t >= {}", n(shadow.t_min))
        };
        self.line(
            sub,
            format!(
                "shadow ray: origin {}, direction {}, {range}: {verdict}",
                v3(shadow.ray.origin),
                v3(shadow.ray.direction)
            ),
        );
        if let Some(lit) = terms.lit {
            self.blinn_phong(sub, terms_bounce, &lit.blinn_phong);
            let scale = match terms.source {
                LightSource::Point(_) => "I/r^2",
                LightSource::Directional(_) => "I",
            };
            self.line(
                sub,
                format!(
                    "adds ({scale})(diffuse + specular) = {} x {} = {}",
                    v3(lit.scale),
                    v3(lit.blinn_phong.sum),
                    v3(lit.term)
                ),
            );
        }
        self.line(item, format!("colour so far {}", v3(terms.color)));
    }

    /// Blinn-Phong's terms, with the numbers of the surface shaded at `bounce`.
    pub(super) fn blinn_phong(&mut self, level: u32, bounce: u32, terms: &BlinnPhong) {
        if terms.n_dot_l <= 0.0 {
            self.line(
                level,
                format!(
                    "n.l = {}: the light is behind the shading normal, nothing added",
                    n(terms.n_dot_l)
                ),
            );
            return;
        }
        let surface = self.surfaces.get(bounce as usize).copied();
        let color = surface.map_or("color".to_owned(), |s| v3(s.color));
        self.line(
            level,
            format!(
                "diffuse  = color max(0, n.l) = {color} x {} = {}",
                n(terms.n_dot_l),
                v3(terms.diffuse)
            ),
        );
        match terms.specular {
            Some(specular) => {
                self.line(
                    level,
                    format!(
                        "h = (l + v)/|l + v| = {}, n.h = {}",
                        v3(specular.h),
                        n(specular.n_dot_h)
                    ),
                );
                let (color, shininess) = surface
                    .map_or(("specular".to_owned(), "shininess".to_owned()), |s| {
                        (v3(s.specular), n(s.shininess))
                    });
                self.line(
                    level,
                    format!(
                        "specular = specular max(0, n.h)^shininess = {color} x {}^{shininess} \
                         = {color} x {} = {}",
                        n(specular.n_dot_h.max(0.0)),
                        n(specular.power),
                        v3(specular.term)
                    ),
                );
            }
            None => self.line(
                level,
                "specular = 0   (the material has no specular colour)",
            ),
        }
    }
}
