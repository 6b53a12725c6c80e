//! Bodies and their materials -> `model::Body`, `model::Material` (meshes built by [`super::mesh`]).

use super::{mesh, Lowerer};
use crate::ast::{self, Dimension};
use ctc_engine::model::{self as m, Formulation, Material, MaterialLaw};

impl Lowerer<'_> {
    pub(super) fn bodies(&mut self) -> (Vec<m::Body>, Vec<Material>) {
        let deck = self.deck;
        let axisymmetric = deck
            .analysis
            .first()
            .and_then(|a| a.dimension.as_ref())
            .is_some_and(|d| d.value == Dimension::Axisymmetric);
        let mut bodies = Vec::new();
        let mut materials: Vec<Material> = Vec::new();
        for b in &deck.bodies {
            let Some(mesh_def) = &b.mesh else {
                self.missing("the mesh", b.name.span);
                continue;
            };
            if self.has_error_in(mesh_def.span) {
                continue;
            }
            let placed = if self.solid {
                match mesh::build_solid(&b.name.name, mesh_def, self.src) {
                    Ok(m) => {
                        let (placed, warnings) =
                            mesh::append_solid(&mut self.mesh3, &b.name.name, m, mesh_def.span);
                        self.diags.extend(warnings);
                        placed
                    }
                    Err(ds) => {
                        self.diags.extend(ds);
                        continue;
                    }
                }
            } else {
                let built = match mesh::build(&b.name.name, mesh_def, self.src) {
                    Ok(mesh) => mesh,
                    Err(ds) => {
                        self.diags.extend(ds);
                        continue;
                    }
                };
                if axisymmetric {
                    if let Some(d) = mesh::negative_radius(&b.name.name, &built, mesh_def.span) {
                        self.diags.push(d);
                        continue;
                    }
                }
                let (placed, warnings) =
                    mesh::append(&mut self.mesh, &b.name.name, built, mesh_def.span);
                self.diags.extend(warnings);
                placed
            };
            self.body_nodes
                .insert(b.name.name.clone(), placed.nodes.clone());
            let material = match self.material_index(b, &mut materials) {
                Some(i) => i,
                None => continue,
            };
            let formulation = match b.formulation.as_ref().map(|f| f.value) {
                Some(ast::FormulationKind::SelectiveReduced) => Formulation::SelectiveReduced,
                _ => Formulation::Full,
            };
            bodies.push(m::Body {
                name: b.name.name.clone(),
                nodes: placed.nodes,
                cells: placed.cells,
                material,
                formulation,
                kinematics: match b.kinematics.as_ref().map(|k| k.value) {
                    Some(ast::KinematicsKind::Finite) => m::Kinematics::Finite,
                    _ => m::Kinematics::Small,
                },
            });
        }
        (bodies, materials)
    }

    /// Index of the body's material in `materials`, adding it on first use.
    pub(super) fn material_index(
        &mut self,
        b: &ast::Body,
        materials: &mut Vec<Material>,
    ) -> Option<usize> {
        let name = b.material.as_ref()?;
        if let Some(i) = materials.iter().position(|m| m.name == name.name) {
            return Some(i);
        }
        let Some(def) = self
            .deck
            .materials
            .iter()
            .find(|m| m.name.name == name.name)
        else {
            self.missing("the material", name.span);
            return None;
        };
        let e = def.elastic.as_ref().or(def.neo_hookean.as_ref());
        let (Some(young), Some(poisson)) = (
            e.and_then(|e| e.young.as_ref()),
            e.and_then(|e| e.poisson.as_ref()),
        ) else {
            self.missing("the elastic constants", def.name.span);
            return None;
        };
        let (young, poisson) = (young.value, poisson.value);
        let law = if def.neo_hookean.is_some() {
            MaterialLaw::NeoHookean { young, poisson }
        } else if def.plastic.is_some() || def.norton_hoff.is_some() {
            let v = |x: &Option<crate::span::Spanned<f64>>| x.as_ref().map(|x| x.value);
            let none = ast::Plastic {
                yield_stress: Some(crate::span::Spanned::new(0.0, def.name.span)),
                hardening: None,
                span: def.name.span,
            };
            // pure Norton-Hoff: no static yield stress
            let p = def.plastic.as_ref().unwrap_or(&none);
            let yield_stress = v(&p.yield_stress);
            let hardening = match p.hardening.as_ref().map(|h| &h.value) {
                None => m::Hardening::Linear {
                    yield_stress: yield_stress?,
                    modulus: 0.0,
                },
                Some(ast::Hardening::Linear { modulus }) => m::Hardening::Linear {
                    yield_stress: yield_stress?,
                    modulus: v(modulus)?,
                },
                Some(ast::Hardening::Swift { k, eps0, n }) => m::Hardening::Swift {
                    k: v(k)?,
                    eps0: v(eps0)?,
                    n: v(n)?,
                },
                Some(ast::Hardening::JohnsonCook { values }) => {
                    let [a, b, n, c, rate0, m, t_ref, t_melt] = values;
                    m::Hardening::JohnsonCook {
                        a: v(a)?,
                        b: v(b)?,
                        n: v(n)?,
                        c: v(c)?,
                        rate0: v(rate0)?,
                        m: v(m)?,
                        t_ref: v(t_ref)?,
                        t_melt: v(t_melt)?,
                        temperature: v(t_ref)?,
                    }
                }
                Some(ast::Hardening::Voce { sigma_inf, delta }) => m::Hardening::Voce {
                    yield_stress: yield_stress?,
                    sigma_inf: v(sigma_inf)?,
                    delta: v(delta)?,
                },
            };
            MaterialLaw::ElastoPlastic {
                young,
                poisson,
                hardening,
                viscosity: match (&def.norton_hoff, &def.viscoplastic) {
                    (Some(n), _) => Some(m::Viscosity::NortonHoff {
                        stress: v(&n.stress)?,
                        rate: v(&n.rate)?,
                        m: v(&n.m)?,
                    }),
                    (None, Some(vp)) => Some(match v(&vp.eta) {
                        Some(eta) => m::Viscosity::Perzyna { eta },
                        None => m::Viscosity::PerzynaPower {
                            rate: v(&vp.rate)?,
                            exponent: v(&vp.exponent)?,
                        },
                    }),
                    (None, None) => None,
                },
            }
        } else {
            MaterialLaw::LinearElastic { young, poisson }
        };
        materials.push(Material {
            name: name.name.clone(),
            law,
            density: def.density.as_ref().map_or(0.0, |d| d.value),
        });
        Some(materials.len() - 1)
    }
}
