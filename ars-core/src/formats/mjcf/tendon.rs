//! `<tendon>`: MuJoCo's tendons, as far as ARS takes them.
//!
//! A fixed tendon is a length made of joint positions (`Σ coef · q`). It acts only
//! through what the file gives it: a limit (`range`, with `limited` true, or auto with a
//! range), a spring (`stiffness`), `damping`, `frictionloss`, or an actuator or sensor on
//! it (those are refused where they are read). A fixed tendon with none of these does
//! nothing to the motion (Gymnasium's and dm_control's humanoids define two, for their
//! users' own use), so it is read and dropped, and the model loads strictly. Any other
//! tendon, and every spatial tendon, is unsupported: an error, or a line in `skipped`
//! with `skip_unsupported`.

use super::defaults::Attrs;
use super::problem::Parsed;
use super::read::Reader;

impl<'a, 'input> Reader<'_, 'a, 'input> {
    /// The `<tendon>` section: each tendon dropped when it does nothing, else
    /// unsupported (see the module docs).
    pub(super) fn tendons(&mut self, node: roxmltree::Node<'a, 'input>) -> Parsed<()> {
        for child in self.tree.elements(node) {
            let tag = child.tag_name().name();
            if tag != "fixed" {
                self.unsupported(&child, &format!("a <{tag}> tendon"))?;
                continue;
            }
            // Tendon defaults are a class's `<tendon>`, whatever the kind.
            let class = child.attribute("class").unwrap_or("main");
            let a = Attrs { node: child, class: self.defaults.get(class).and_then(|c| c.get("tendon")) };
            let limited = match a.get("limited") {
                Some("true") => true,
                Some("false") => false,
                _ => a.get("range").is_some(),
            };
            let mut acting = Vec::new();
            if limited {
                acting.push("a limit");
            }
            for (attribute, what) in [("stiffness", "a spring"), ("damping", "damping"), ("frictionloss", "friction")] {
                if a.number(attribute)?.is_some_and(|x| x != 0.0) {
                    acting.push(what);
                }
            }
            if !acting.is_empty() {
                self.unsupported(&child, &format!("a fixed tendon with {}", acting.join(", ")))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::formats::mjcf::MjcfOptions;
    use crate::simulation::Simulation;

    const BODY: &str = "<worldbody><body><joint name='a'/><geom size='.1'/>\
                        <body pos='0 0 1'><joint name='b'/><geom size='.1'/></body></body></worldbody>";

    fn load(tendon: &str, defaults: &str) -> Result<Vec<String>, String> {
        let text = format!("<mujoco><default>{defaults}</default>{BODY}<tendon>{tendon}</tendon></mujoco>");
        let mut sim = Simulation::new().unwrap();
        sim.load_mjcf_text(&text, "t.xml", &MjcfOptions::new()).map(|m| m.skipped).map_err(|e| e.to_string())
    }

    #[test]
    fn a_fixed_tendon_that_does_nothing_loads_strictly_and_one_that_acts_is_refused() {
        // Gymnasium's humanoid's: two joints, nothing else.
        let coupled = "<joint joint='a' coef='-1'/><joint joint='b' coef='1'/>";
        assert_eq!(load(&format!("<fixed name='t'>{coupled}</fixed>"), ""), Ok(Vec::new()));
        assert_eq!(load(&format!("<fixed limited='false' range='-1 1'>{coupled}</fixed>"), ""), Ok(Vec::new()));
        for (tendon, defaults, says) in [
            (format!("<fixed range='-1 1'>{coupled}</fixed>"), "", "a limit"),
            (format!("<fixed damping='2'>{coupled}</fixed>"), "", "damping"),
            (format!("<fixed frictionloss='2'>{coupled}</fixed>"), "", "friction"),
            // A class's spring is the tendon's.
            (format!("<fixed>{coupled}</fixed>"), "<tendon stiffness='0.4'/>", "a spring"),
            ("<spatial><site site='s'/></spatial>".to_string(), "", "a <spatial> tendon"),
        ] {
            let error = load(&tendon, defaults).unwrap_err();
            assert!(error.contains(says) && error.contains("skip_unsupported"), "{error}");
        }
    }
}
