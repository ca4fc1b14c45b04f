//! SVG outlines, read through `roxmltree` (a read-only XML tree) and `svgtypes` (SVG's
//! micro-syntaxes).
//!
//! Rules (every rule that moves geometry is applied or refused, never ignored):
//! - **What counts**: each rendered `<path>` subpath, `<rect>` (rounded corners too),
//!   `<circle>`, `<ellipse>`, `<polygon>`, and `<polyline>` whose ends meet; a subpath or
//!   polyline counts as closed when it ends with `z` or its ends meet within
//!   [`JOIN_TOLERANCE_MM`]; open ones and `<line>` are errors naming the element.
//! - **Applied**: `transform` attributes of every kind on the element and all its ancestors,
//!   nested `<svg x y width height viewBox preserveAspectRatio>` viewports, `<use x y href>`
//!   (of shapes, groups, `<symbol>` and `<svg>`; local `#id` references), lengths with units
//!   (px = 1/96 in, mm, cm, in, pt, pc, % of the viewport).
//! - **Root size**: when the root `<svg>` has a width and height with an absolute unit (a plain
//!   number is px, 1/96 in; a missing one follows the viewBox's aspect ratio), the drawing is
//!   mapped to that size in mm, through its viewBox if any (else 1 user unit = 1 px). Without
//!   such a size (none, or %) a user unit is 1 mm and the viewBox is not applied. Then y is
//!   flipped (y' = −y): SVG's y points down, the planner's up.
//! - **Refused**: CSS `transform` or `transform-origin` in a `style` attribute, a `<style>`
//!   sheet setting `transform`, `display` or `visibility`, em/ex lengths, external `<use>`
//!   references, `<use>` cycles or nesting deeper than [`MAX_USE_DEPTH`], transforms that
//!   flatten the drawing, non-finite numbers.
//! - **Not read** (not rendered, or not outlines): elements under `<defs>`, `<symbol>`,
//!   `<clipPath>`, `<mask>`, `<pattern>`, `<marker>` and the like (unless used by `<use>`),
//!   elements of foreign namespaces, `display:none` subtrees, `visibility:hidden` elements,
//!   `<text>` and `<image>`, and the non-chosen children of `<switch>` (the first child without
//!   conditional attributes is rendered). Clipping and stroke widths are not applied: outlines
//!   are read as the geometry drawn.

use super::svg_path::{self, Subpath, quoted};
use super::{Affine, Budget, JOIN_TOLERANCE_MM, Loop, flatten};
use crate::error::{Error, num};
use crate::geom::{P2, p2};
use roxmltree::{Document, Node};
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, TAU};
use svgtypes::{Align, AspectRatio, Length, LengthUnit, Transform, ViewBox};

/// Deepest nesting of `<use>` references read.
pub const MAX_USE_DEPTH: usize = 16;
/// Millimetres per CSS pixel (1/96 in).
pub const MM_PER_PX: f64 = 25.4 / 96.0;
const XLINK: &str = "http://www.w3.org/1999/xlink";

/// Elements whose content is not rendered where it stands.
const UNRENDERED: [&str; 17] = [
    "defs",
    "symbol",
    "clipPath",
    "mask",
    "pattern",
    "marker",
    "linearGradient",
    "radialGradient",
    "filter",
    "title",
    "desc",
    "metadata",
    "style",
    "script",
    "foreignObject",
    "text",
    "image",
];

/// Where the content of an element lands: user units to mm, the viewport's size in user
/// units (for % lengths; `None` when the drawing has no size), and whether it is visible.
#[derive(Clone, Copy)]
struct Ctx {
    m: Affine,
    viewport: Option<(f64, f64)>,
    visible: bool,
    uses: usize,
}

#[derive(Clone, Copy)]
enum Axis {
    X,
    Y,
    Diagonal,
}

/// The loops of an SVG file.
pub(crate) fn loops(name: &str, text: &str, budget: &mut Budget) -> Result<Vec<Loop>, Error> {
    let nodes = text.bytes().filter(|&b| b == b'<').count();
    if nodes > super::MAX_SVG_NODES {
        return Err(Error::File(format!(
            "{name}: {nodes} markup items (elements, comments): more than the {} an SVG file may have",
            super::MAX_SVG_NODES
        )));
    }
    let doc = Document::parse(text).map_err(|e| Error::File(format!("{name}: not a readable SVG file ({e})")))?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(Error::File(format!("{name}: the root element is <{}>, not <svg>", root.tag_name().name())));
    }
    let ids: HashMap<&str, Node> =
        doc.descendants().filter_map(|n| n.attribute("id").map(|id| (id, n))).collect::<HashMap<_, _>>();
    let mut reader = Reader { name, doc: &doc, ns: root.tag_name().namespace(), ids, budget, loops: Vec::new() };
    reader.check_style_sheets()?;
    let ctx = reader.root_ctx(root)?;
    reader.children(root, &ctx)?;
    Ok(reader.loops)
}

struct Reader<'a, 'input, 'b> {
    name: &'a str,
    doc: &'a Document<'input>,
    ns: Option<&'a str>,
    ids: HashMap<&'a str, Node<'a, 'input>>,
    budget: &'b mut Budget,
    loops: Vec<Loop>,
}

/// The declarations of a `style` attribute: (property in lower case, value).
fn declarations(style: &str) -> Vec<(String, &str)> {
    style.split(';').filter_map(|d| d.split_once(':')).map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim())).collect()
}

/// A property of `node`: its `style` declaration, else its presentation attribute.
fn property<'a>(node: Node<'a, '_>, key: &str) -> Option<&'a str> {
    let from_style = node.attribute("style").and_then(|s| declarations(s).into_iter().rev().find(|(k, _)| k == key));
    from_style.map(|(_, v)| v).or_else(|| node.attribute(key)).map(str::trim)
}

impl<'a, 'input> Reader<'a, 'input, '_> {
    /// "<path id=\"a\"> (line 3)".
    fn element_name(&self, node: Node) -> String {
        let pos = self.doc.text_pos_at(node.range().start);
        let id = node.attribute("id").map(|id| format!(" id={id:?}")).unwrap_or_default();
        format!("<{}{id}> (line {})", node.tag_name().name(), pos.row)
    }

    /// "file.svg: <path id=\"a\"> (line 3)" for messages.
    fn what(&self, node: Node) -> String {
        format!("{}: {}", self.name, self.element_name(node))
    }

    fn err(&self, node: Node, why: &str) -> Error {
        Error::File(format!("{}: {why}", self.what(node)))
    }

    /// `<style>` sheets may style colours, not geometry: one that sets transform, display or
    /// visibility is refused (its selectors are not matched here).
    fn check_style_sheets(&self) -> Result<(), Error> {
        for n in self.doc.descendants().filter(|n| n.is_element() && n.tag_name().name() == "style") {
            let css: String = n.descendants().filter_map(|t| t.text()).collect();
            for part in css.split(['{', '}', ';']) {
                if let Some((k, _)) = part.split_once(':') {
                    let k = k.trim().to_ascii_lowercase();
                    if matches!(k.as_str(), "transform" | "transform-origin" | "display" | "visibility") {
                        return Err(self.err(
                            n,
                            &format!("the style sheet sets {k}, which is not applied here: set it as an attribute"),
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// A length attribute in user units (`default` when absent).
    fn length(&self, node: Node, attr: &str, default: f64, axis: Axis, vp: Option<(f64, f64)>) -> Result<f64, Error> {
        let Some(text) = node.attribute(attr) else { return Ok(default) };
        let bad = |why: &str| self.err(node, &format!("{attr}={}: {why}", quoted(text)));
        let l: Length = text.parse().map_err(|e| bad(&format!("{e}")))?;
        if !l.number.is_finite() {
            return Err(bad("not a finite number"));
        }
        let px = |mm: f64| l.number * mm / MM_PER_PX;
        Ok(match l.unit {
            LengthUnit::None | LengthUnit::Px => l.number,
            LengthUnit::Mm => px(1.0),
            LengthUnit::Cm => px(10.0),
            LengthUnit::In => px(25.4),
            LengthUnit::Pt => px(25.4 / 72.0),
            LengthUnit::Pc => px(25.4 / 6.0),
            LengthUnit::Percent => {
                let Some((w, h)) = vp else {
                    return Err(bad("a percentage needs a viewport size (give the root <svg> a width and height)"));
                };
                let whole = match axis {
                    Axis::X => w,
                    Axis::Y => h,
                    Axis::Diagonal => ((w * w + h * h) / 2.0).sqrt(),
                };
                l.number / 100.0 * whole
            }
            LengthUnit::Em | LengthUnit::Ex => return Err(bad("font-relative units (em, ex) are not supported")),
        })
    }

    /// The root's map (user units to mm, y flipped) and viewport.
    fn root_ctx(&self, root: Node) -> Result<Ctx, Error> {
        let size = |attr: &str| -> Result<Option<f64>, Error> {
            match root.attribute(attr).map(|t| (t, t.parse::<Length>())) {
                None => Ok(None),
                Some((t, Err(e))) => Err(self.err(root, &format!("{attr}={}: {e}", quoted(t)))),
                Some((_, Ok(l))) if l.unit == LengthUnit::Percent => Ok(None),
                Some((_, Ok(_))) => Ok(Some(self.length(root, attr, 0.0, Axis::X, None)? * MM_PER_PX)),
            }
        };
        let (w, h) = (size("width")?, size("height")?);
        let vb = self.view_box(root)?;
        let (w, h) = match (w, h, vb) {
            (Some(w), None, Some(vb)) => (Some(w), Some(w * vb.h / vb.w)),
            (None, Some(h), Some(vb)) => (Some(h * vb.w / vb.h), Some(h)),
            other => (other.0, other.1),
        };
        let flip = Affine::scale(1.0, -1.0);
        let (m, viewport) = match (w, h, vb) {
            (Some(w), Some(h), Some(vb)) => (self.view_box_map(root, vb, w, h)?, Some((vb.w, vb.h))),
            (Some(w), Some(h), None) => (Affine::scale(MM_PER_PX, MM_PER_PX), Some((w / MM_PER_PX, h / MM_PER_PX))),
            (_, _, vb) => (Affine::IDENTITY, vb.map(|vb| (vb.w, vb.h))),
        };
        let m = flip.then(&m).then(&self.transform(root)?);
        self.regular(root, &m)?;
        Ok(Ctx { m, viewport, visible: true, uses: 0 })
    }

    fn view_box(&self, node: Node) -> Result<Option<ViewBox>, Error> {
        match node.attribute("viewBox") {
            None => Ok(None),
            Some(t) => match t.parse::<ViewBox>() {
                Ok(vb) if [vb.x, vb.y, vb.w, vb.h].iter().all(|v| v.is_finite()) => Ok(Some(vb)),
                Ok(_) => Err(self.err(node, &format!("viewBox={}: not finite", quoted(t)))),
                Err(e) => Err(self.err(node, &format!("viewBox={}: {e}", quoted(t)))),
            },
        }
    }

    /// The viewBox-to-viewport map for a viewport of `w` × `h` at the origin
    /// (preserveAspectRatio: alignment, meet or slice, or none).
    fn view_box_map(&self, node: Node, vb: ViewBox, w: f64, h: f64) -> Result<Affine, Error> {
        let par: AspectRatio = match node.attribute("preserveAspectRatio") {
            None => AspectRatio { defer: false, align: Align::XMidYMid, slice: false },
            Some(t) => t.parse().map_err(|e| self.err(node, &format!("preserveAspectRatio={}: {e}", quoted(t))))?,
        };
        let (sx, sy) = (w / vb.w, h / vb.h);
        if par.align == Align::None {
            return Ok(Affine::scale(sx, sy).then(&Affine::translate(-vb.x, -vb.y)));
        }
        let s = if par.slice { sx.max(sy) } else { sx.min(sy) };
        let (fx, fy) = match par.align {
            Align::XMinYMin => (0.0, 0.0),
            Align::XMidYMin => (0.5, 0.0),
            Align::XMaxYMin => (1.0, 0.0),
            Align::XMinYMid => (0.0, 0.5),
            Align::XMinYMax => (0.0, 1.0),
            Align::XMidYMax => (0.5, 1.0),
            Align::XMaxYMid => (1.0, 0.5),
            Align::XMaxYMax => (1.0, 1.0),
            Align::XMidYMid | Align::None => (0.5, 0.5),
        };
        let (tx, ty) = (fx * (w - vb.w * s), fy * (h - vb.h * s));
        Ok(Affine::translate(tx, ty).then(&Affine::scale(s, s)).then(&Affine::translate(-vb.x, -vb.y)))
    }

    /// The element's `transform` attribute (identity when absent); CSS transforms are refused.
    fn transform(&self, node: Node) -> Result<Affine, Error> {
        for key in ["transform", "transform-origin", "transform-box"] {
            let in_style = node.attribute("style").is_some_and(|s| declarations(s).iter().any(|(k, _)| k == key));
            if in_style {
                return Err(
                    self.err(node, &format!("CSS {key} in style is not supported: use the transform attribute"))
                );
            }
        }
        if let Some(t) = node.attribute("transform-origin") {
            return Err(self.err(node, &format!("transform-origin={} is not supported", quoted(t))));
        }
        let Some(text) = node.attribute("transform") else { return Ok(Affine::IDENTITY) };
        let t: Transform = text.parse().map_err(|e| self.err(node, &format!("transform={}: {e}", quoted(text))))?;
        let m = Affine { a: t.a, b: t.b, c: t.c, d: t.d, e: t.e, f: t.f };
        if ![m.a, m.b, m.c, m.d, m.e, m.f].iter().all(|v| v.is_finite()) {
            return Err(self.err(node, &format!("transform={}: not finite", quoted(text))));
        }
        Ok(m)
    }

    /// The map must keep areas (a zero scale would flatten every loop).
    fn regular(&self, node: Node, m: &Affine) -> Result<(), Error> {
        if m.is_regular() {
            Ok(())
        } else {
            Err(self.err(node, "its transforms flatten the drawing (zero or non-finite scale)"))
        }
    }

    fn children(&mut self, node: Node<'a, 'input>, ctx: &Ctx) -> Result<(), Error> {
        for child in node.children().filter(Node::is_element) {
            self.element(child, ctx)?;
        }
        Ok(())
    }

    fn element(&mut self, node: Node<'a, 'input>, ctx: &Ctx) -> Result<(), Error> {
        if node.tag_name().namespace() != self.ns {
            return Ok(()); // a foreign namespace: not SVG, not rendered
        }
        if property(node, "display") == Some("none") {
            return Ok(());
        }
        let visible = match property(node, "visibility") {
            Some("hidden" | "collapse") => false,
            Some("visible") => true,
            _ => ctx.visible,
        };
        let tag = node.tag_name().name();
        if UNRENDERED.contains(&tag) {
            return Ok(());
        }
        let m = ctx.m.then(&self.transform(node)?);
        let ctx = Ctx { m, visible, ..*ctx };
        match tag {
            "g" | "a" => self.children(node, &ctx),
            "switch" => {
                let conditional = ["requiredFeatures", "requiredExtensions", "systemLanguage"];
                let chosen = node
                    .children()
                    .filter(|c| c.is_element() && c.tag_name().namespace() == self.ns)
                    .find(|c| conditional.iter().all(|a| !c.has_attribute(*a)));
                chosen.map_or(Ok(()), |c| self.element(c, &ctx))
            }
            "svg" => self.viewport(node, &ctx, None),
            "use" => self.use_element(node, &ctx),
            "path" | "rect" | "circle" | "ellipse" | "polygon" | "polyline" | "line" if visible => {
                self.regular(node, &ctx.m)?;
                self.shape(node, &ctx)
            }
            _ => Ok(()), // unknown or invisible: nothing rendered
        }
    }

    /// A nested viewport: `<svg>`, or a `<symbol>`/`<svg>` drawn by a `<use>` (`sized_by`, whose
    /// width and height replace the element's). Its x, y, width, height (default 100%) are in
    /// the parent's user units.
    fn viewport(&mut self, node: Node<'a, 'input>, ctx: &Ctx, sized_by: Option<Node>) -> Result<(), Error> {
        let vp = ctx.viewport;
        let dim = |attr: &str, axis: Axis| -> Result<f64, Error> {
            let from = sized_by.filter(|u| u.has_attribute(attr)).unwrap_or(node);
            match (from.has_attribute(attr), vp) {
                (true, _) => self.length(from, attr, 0.0, axis, vp),
                (false, Some((w, h))) => Ok(if matches!(axis, Axis::X) { w } else { h }),
                (false, None) => Err(self.err(from, &format!("{attr} is needed here (the drawing has no size)"))),
            }
        };
        let (w, h) = (dim("width", Axis::X)?, dim("height", Axis::Y)?);
        if w < 0.0 || h < 0.0 {
            return Err(self.err(node, "a negative width or height"));
        }
        if w == 0.0 || h == 0.0 {
            return Ok(()); // a zero-sized viewport renders nothing
        }
        let (x, y) = (self.length(node, "x", 0.0, Axis::X, vp)?, self.length(node, "y", 0.0, Axis::Y, vp)?);
        let (map, inner) = match self.view_box(node)? {
            Some(vb) => (self.view_box_map(node, vb, w, h)?, (vb.w, vb.h)),
            None => (Affine::IDENTITY, (w, h)),
        };
        let m = ctx.m.then(&Affine::translate(x, y)).then(&map);
        self.regular(node, &m)?;
        self.children(node, &Ctx { m, viewport: Some(inner), ..*ctx })
    }

    fn use_element(&mut self, node: Node<'a, 'input>, ctx: &Ctx) -> Result<(), Error> {
        let Some(href) = node.attribute("href").or_else(|| node.attribute((XLINK, "href"))) else {
            return Ok(()); // refers to nothing: renders nothing
        };
        let Some(id) = href.trim().strip_prefix('#') else {
            return Err(
                self.err(node, &format!("href={}: only references within the file (#id) are read", quoted(href)))
            );
        };
        let Some(target) = self.ids.get(id).copied() else {
            return Err(self.err(node, &format!("href={}: no element has this id", quoted(href))));
        };
        if target.ancestors().any(|a| a == node) || node.ancestors().any(|a| a == target) {
            return Err(self.err(node, &format!("href={}: refers to itself or its own ancestor", quoted(href))));
        }
        if ctx.uses >= MAX_USE_DEPTH {
            return Err(self.err(node, &format!("<use> nested more than {MAX_USE_DEPTH} deep")));
        }
        self.budget.expand(&self.what(node))?;
        let vp = ctx.viewport;
        let (x, y) = (self.length(node, "x", 0.0, Axis::X, vp)?, self.length(node, "y", 0.0, Axis::Y, vp)?);
        let ctx = Ctx { m: ctx.m.then(&Affine::translate(x, y)), uses: ctx.uses + 1, ..*ctx };
        if target.tag_name().namespace() != self.ns {
            return Ok(());
        }
        match target.tag_name().name() {
            "symbol" | "svg" => {
                if property(target, "display") == Some("none") {
                    return Ok(());
                }
                let m = ctx.m.then(&self.transform(target)?);
                self.viewport(target, &Ctx { m, ..ctx }, Some(node))
            }
            _ => self.element(target, &ctx),
        }
    }

    /// A shape's loops in mm.
    fn shape(&mut self, node: Node<'a, 'input>, ctx: &Ctx) -> Result<(), Error> {
        let what = self.what(node);
        let tol = ctx.m.tolerance();
        let vp = ctx.viewport;
        let len = |attr: &str, axis: Axis| self.length(node, attr, 0.0, axis, vp);
        let subpaths: Vec<Subpath> = match node.tag_name().name() {
            "path" => svg_path::path_data(node.attribute("d").unwrap_or(""), tol, self.budget, &what)?,
            "polygon" | "polyline" => {
                let pts = svg_path::points(node.attribute("points").unwrap_or(""), self.budget, &what)?;
                let closed = node.tag_name().name() == "polygon";
                if pts.len() > 1 { vec![Subpath { pts, closed }] } else { Vec::new() }
            }
            "line" => return Err(self.err(node, "a <line> is not a closed loop: draw the outline as a closed shape")),
            "rect" => {
                let (x, y, w, h) =
                    (len("x", Axis::X)?, len("y", Axis::Y)?, len("width", Axis::X)?, len("height", Axis::Y)?);
                if w < 0.0 || h < 0.0 {
                    return Err(self.err(node, &format!("width {} and height {} must not be negative", num(w), num(h))));
                }
                if w == 0.0 || h == 0.0 {
                    return Ok(()); // not rendered
                }
                let (rx, ry) = self.radii(node, vp, "rx", "ry")?;
                let (rx, ry) = (rx.min(w / 2.0), ry.min(h / 2.0));
                vec![Subpath { pts: self.rect(x, y, w, h, rx, ry, tol, &what)?, closed: true }]
            }
            "circle" | "ellipse" => {
                let (cx, cy) = (len("cx", Axis::X)?, len("cy", Axis::Y)?);
                let (rx, ry) = if node.tag_name().name() == "circle" {
                    let r = len("r", Axis::Diagonal)?;
                    (r, r)
                } else {
                    self.radii(node, vp, "rx", "ry")?
                };
                if rx < 0.0 || ry < 0.0 {
                    return Err(self.err(node, "a negative radius"));
                }
                if rx == 0.0 || ry == 0.0 {
                    return Ok(()); // not rendered
                }
                let pts = flatten::ellipse_loop(p2(cx, cy), p2(rx, 0.0), p2(0.0, ry), TAU, tol, self.budget, &what)?;
                vec![Subpath { pts, closed: true }]
            }
            _ => Vec::new(),
        };
        let many = subpaths.len() > 1;
        for (k, s) in subpaths.into_iter().enumerate() {
            let mut pts: Vec<P2> = s.pts.iter().map(|p| ctx.m.apply(*p)).collect();
            let gap = (pts[0] - pts[pts.len() - 1]).norm();
            let element = self.element_name(node);
            let source = if many { format!("{element} subpath {}", k + 1) } else { element };
            if gap <= JOIN_TOLERANCE_MM {
                pts.pop();
            } else if !s.closed {
                return Err(Error::File(format!(
                    "{}: {source} is open (its end is {} mm from its start): every outline must be closed",
                    self.name,
                    num(gap)
                )));
            }
            self.loops.push(Loop { pts, source });
        }
        Ok(())
    }

    /// rx and ry of a rect or ellipse: one given (or "auto") stands for both.
    fn radii(&self, node: Node, vp: Option<(f64, f64)>, kx: &str, ky: &str) -> Result<(f64, f64), Error> {
        let given = |k: &str| node.attribute(k).is_some_and(|v| v.trim() != "auto");
        let rx = if given(kx) { Some(self.length(node, kx, 0.0, Axis::X, vp)?) } else { None };
        let ry = if given(ky) { Some(self.length(node, ky, 0.0, Axis::Y, vp)?) } else { None };
        let (rx, ry) = match (rx, ry) {
            (Some(x), Some(y)) => (x, y),
            (Some(x), None) => (x, x),
            (None, Some(y)) => (y, y),
            (None, None) => (0.0, 0.0),
        };
        if rx < 0.0 || ry < 0.0 {
            return Err(self.err(node, &format!("radii {} and {} must not be negative", num(rx), num(ry))));
        }
        Ok((rx, ry))
    }

    /// A rectangle's loop (user units) with corners rounded by quarter ellipses rx × ry.
    #[allow(clippy::too_many_arguments)]
    fn rect(
        &mut self,
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        rx: f64,
        ry: f64,
        tol: f64,
        what: &str,
    ) -> Result<Vec<P2>, Error> {
        self.budget.take(4.0, what)?;
        if rx == 0.0 || ry == 0.0 {
            return Ok(vec![p2(x, y), p2(x + w, y), p2(x + w, y + h), p2(x, y + h)]);
        }
        // corners clockwise on screen (y down): top right, bottom right, bottom left, top left
        let corners = [
            (x + w - rx, y + ry, -FRAC_PI_2),
            (x + w - rx, y + h - ry, 0.0),
            (x + rx, y + h - ry, FRAC_PI_2),
            (x + rx, y + ry, -2.0 * FRAC_PI_2),
        ];
        let mut pts = vec![p2(x + rx, y)];
        for (cx, cy, t0) in corners {
            let start = p2(cx + rx * t0.cos(), cy + ry * t0.sin());
            if (start - pts[pts.len() - 1]).norm() > 0.0 {
                pts.push(start);
            }
            pts.extend(flatten::ellipse_arc(
                start,
                p2(rx, 0.0),
                p2(0.0, ry),
                t0,
                FRAC_PI_2,
                None,
                tol,
                self.budget,
                what,
            )?);
        }
        if (pts[0] - pts[pts.len() - 1]).norm() <= 1e-12 * (w + h) {
            pts.pop();
        }
        Ok(pts)
    }
}
