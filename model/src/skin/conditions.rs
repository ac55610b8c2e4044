//! What a face has besides its anatomy: freckles, moles, redness, acne, hyperpigmentation,
//! under-eye darkness and visible veins, each an amount in [0, 1]. Written as
//! `freckles=0.6,redness=0.4` (every amount not named is 0; `none` or an empty string is all 0),
//! and in JSON as `{"freckles": 0.6, "redness": 0.4}`. Where and how each is drawn:
//! [`super::generate`].

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

/// One skin condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Condition {
    /// Ephelides: small light-brown macules on the sun-exposed cheeks, nose and forehead.
    Freckles,
    /// Melanocytic naevi: a few dark brown spots anywhere on the face.
    Moles,
    /// Rosacea's persistent centrofacial erythema: more blood over the cheeks and nose.
    Redness,
    /// Inflammatory acne papules: small red bumps on the forehead, cheeks and chin.
    Acne,
    /// Post-inflammatory hyperpigmentation: brown macules where acne was.
    Hyperpigmentation,
    /// Periorbital darkness: more melanin and less oxygenated blood under the eyes.
    UnderEye,
    /// Visible veins: bluish lines of deoxygenated blood on the temples and eyelids.
    Veins,
}

impl Condition {
    /// Every condition, in the order they are printed.
    pub const ALL: [Condition; 7] = [
        Condition::Freckles,
        Condition::Moles,
        Condition::Redness,
        Condition::Acne,
        Condition::Hyperpigmentation,
        Condition::UnderEye,
        Condition::Veins,
    ];

    /// Its key in `freckles=0.6,...` and in JSON.
    pub const fn key(self) -> &'static str {
        match self {
            Condition::Freckles => "freckles",
            Condition::Moles => "moles",
            Condition::Redness => "redness",
            Condition::Acne => "acne",
            Condition::Hyperpigmentation => "hyperpigmentation",
            Condition::UnderEye => "under_eye",
            Condition::Veins => "veins",
        }
    }

    /// The condition with this key (exact), if any.
    pub fn parse(key: &str) -> Option<Condition> {
        Condition::ALL.into_iter().find(|c| c.key() == key)
    }

    fn keys() -> String {
        Condition::ALL.map(|c| c.key()).join(", ")
    }
}

impl fmt::Display for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// Why a conditions string or object was refused; every message names the key or value at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConditionError {
    /// A key that is no condition.
    #[error("unknown skin condition `{key}` (the conditions: {known})")]
    UnknownKey {
        /// The key given.
        key: String,
        /// The keys there are.
        known: String,
    },
    /// An item without `=`.
    #[error("`{item}`: expected KEY=AMOUNT, e.g. `freckles=0.6`")]
    Syntax {
        /// The item.
        item: String,
    },
    /// A value that is not a number.
    #[error("`{key}={value}`: the amount is not a number (an amount is in [0, 1])")]
    NotANumber {
        /// The condition.
        key: String,
        /// The text given.
        value: String,
    },
    /// A number outside [0, 1] (or NaN).
    #[error("`{key}` = {value}: the amount must be in [0, 1]")]
    OutOfRange {
        /// The condition.
        key: String,
        /// The amount given.
        value: f64,
    },
    /// The same key twice.
    #[error("`{key}` is given twice")]
    Duplicate {
        /// The condition.
        key: String,
    },
}

/// The amount of each [`Condition`], each in [0, 1] (0 = absent, 1 = the most the generator
/// draws). Built by [`SkinConditions::set`] or parsed, so always in range.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "BTreeMap<String, f64>", into = "BTreeMap<String, f64>")]
pub struct SkinConditions {
    amounts: [f64; 7],
}

impl SkinConditions {
    /// No condition.
    pub const NONE: SkinConditions = SkinConditions { amounts: [0.0; 7] };

    /// The amount of `c`.
    pub fn get(&self, c: Condition) -> f64 {
        self.amounts[c as usize]
    }

    /// Sets the amount of `c`.
    ///
    /// # Errors
    /// [`ConditionError::OutOfRange`] for an amount outside [0, 1] or NaN (nothing changes).
    pub fn set(&mut self, c: Condition, amount: f64) -> Result<(), ConditionError> {
        if !(0.0..=1.0).contains(&amount) {
            return Err(ConditionError::OutOfRange { key: c.key().into(), value: amount });
        }
        self.amounts[c as usize] = amount;
        Ok(())
    }

    /// These conditions with `c` at `amount` (see [`SkinConditions::set`]).
    ///
    /// # Errors
    /// As [`SkinConditions::set`].
    pub fn with(mut self, c: Condition, amount: f64) -> Result<SkinConditions, ConditionError> {
        self.set(c, amount)?;
        Ok(self)
    }

    /// Whether every amount is 0.
    pub fn is_none(&self) -> bool {
        self.amounts.iter().all(|&a| a == 0.0)
    }

    /// The conditions whose amount is not 0, with their amounts, in [`Condition::ALL`]'s order.
    pub fn present(&self) -> impl Iterator<Item = (Condition, f64)> + '_ {
        Condition::ALL.into_iter().map(|c| (c, self.get(c))).filter(|&(_, a)| a != 0.0)
    }

    fn from_pairs<'a>(pairs: impl IntoIterator<Item = (&'a str, f64)>) -> Result<SkinConditions, ConditionError> {
        let mut out = SkinConditions::NONE;
        let mut seen = [false; 7];
        for (key, amount) in pairs {
            let c = Condition::parse(key)
                .ok_or_else(|| ConditionError::UnknownKey { key: key.into(), known: Condition::keys() })?;
            if std::mem::replace(&mut seen[c as usize], true) {
                return Err(ConditionError::Duplicate { key: key.into() });
            }
            out.set(c, amount)?;
        }
        Ok(out)
    }
}

impl FromStr for SkinConditions {
    type Err = ConditionError;

    /// `KEY=AMOUNT` items separated by commas (spaces around them allowed); `none` or an empty
    /// string: no condition.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if s.is_empty() || s == "none" {
            return Ok(SkinConditions::NONE);
        }
        let mut pairs = Vec::new();
        for item in s.split(',') {
            let item = item.trim();
            let (key, value) = item.split_once('=').ok_or_else(|| ConditionError::Syntax { item: item.into() })?;
            let (key, value) = (key.trim(), value.trim());
            if Condition::parse(key).is_none() {
                return Err(ConditionError::UnknownKey { key: key.into(), known: Condition::keys() });
            }
            let amount: f64 =
                value.parse().map_err(|_| ConditionError::NotANumber { key: key.into(), value: value.into() })?;
            pairs.push((key, amount));
        }
        SkinConditions::from_pairs(pairs)
    }
}

impl fmt::Display for SkinConditions {
    /// The amounts that are not 0, `key=amount` in [`Condition::ALL`]'s order (Rust's shortest
    /// round-trip form of each number, so parsing the text gives these conditions back), or
    /// `none`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_none() {
            return f.write_str("none");
        }
        let items: Vec<String> = self.present().map(|(c, a)| format!("{}={a}", c.key())).collect();
        f.write_str(&items.join(","))
    }
}

impl TryFrom<BTreeMap<String, f64>> for SkinConditions {
    type Error = ConditionError;

    fn try_from(map: BTreeMap<String, f64>) -> Result<Self, Self::Error> {
        SkinConditions::from_pairs(map.iter().map(|(k, &v)| (k.as_str(), v)))
    }
}

impl From<SkinConditions> for BTreeMap<String, f64> {
    fn from(c: SkinConditions) -> Self {
        c.present().map(|(c, a)| (c.key().to_string(), a)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_and_names_what_is_wrong() {
        let c: SkinConditions = "freckles=0.6, redness=0.4".parse().unwrap();
        assert_eq!(c.get(Condition::Freckles), 0.6);
        assert_eq!(c.get(Condition::Redness), 0.4);
        assert_eq!(c.get(Condition::Moles), 0.0);
        assert_eq!(c.to_string(), "freckles=0.6,redness=0.4");
        assert_eq!(c.to_string().parse::<SkinConditions>().unwrap(), c);
        assert_eq!("none".parse::<SkinConditions>().unwrap(), SkinConditions::NONE);
        assert_eq!("".parse::<SkinConditions>().unwrap().to_string(), "none");
        let all: Vec<String> = Condition::ALL.iter().map(|c| format!("{c}=1")).collect();
        let all: SkinConditions = all.join(",").parse().unwrap();
        assert!(Condition::ALL.iter().all(|&c| all.get(c) == 1.0));

        let err = |s: &str| s.parse::<SkinConditions>().unwrap_err().to_string();
        let e = err("freckles=0.6,wrinkles=0.2");
        assert!(e.contains("`wrinkles`") && e.contains("freckles, moles") && e.contains("veins"), "{e}");
        let e = err("redness=1.5");
        assert!(e.contains("`redness` = 1.5") && e.contains("[0, 1]"), "{e}");
        let e = err("acne=-0.1");
        assert!(e.contains("`acne` = -0.1") && e.contains("[0, 1]"), "{e}");
        let e = err("moles=lots");
        assert!(e.contains("`moles=lots`") && e.contains("not a number"), "{e}");
        let e = err("veins=NaN");
        assert!(e.contains("`veins` = NaN"), "{e}");
        let e = err("freckles");
        assert!(e.contains("`freckles`") && e.contains("KEY=AMOUNT"), "{e}");
        let e = err("acne=0.1,acne=0.2");
        assert!(e.contains("`acne` is given twice"), "{e}");
    }

    #[test]
    fn json_holds_the_present_amounts_and_refuses_bad_ones() {
        let c = SkinConditions::NONE.with(Condition::UnderEye, 0.25).unwrap().with(Condition::Veins, 1.0).unwrap();
        let json = serde_json::to_string(&c).unwrap();
        assert_eq!(json, r#"{"under_eye":0.25,"veins":1.0}"#);
        assert_eq!(serde_json::from_str::<SkinConditions>(&json).unwrap(), c);
        assert_eq!(serde_json::from_str::<SkinConditions>("{}").unwrap(), SkinConditions::NONE);
        let e = serde_json::from_str::<SkinConditions>(r#"{"freckle": 0.5}"#).unwrap_err().to_string();
        assert!(e.contains("`freckle`") && e.contains("freckles"), "{e}");
        let e = serde_json::from_str::<SkinConditions>(r#"{"moles": 2}"#).unwrap_err().to_string();
        assert!(e.contains("`moles` = 2"), "{e}");
        assert!(SkinConditions::NONE.with(Condition::Acne, f64::INFINITY).is_err());
    }
}
