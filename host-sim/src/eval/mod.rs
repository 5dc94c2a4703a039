//! Scoring runs against the truth: the [`metrics`] (OSPA, GOSPA, label switches, ...), the scoring of a
//! run's MAP estimates ([`score`]), births and their confirmation ([`births`]), and the exactness of a
//! bounded tracker against the unbounded reference ([`exactness`]), the errors of observed and unobserved
//! catalogue objects apart ([`observed`]), scoring a whole catalogue component by component
//! ([`components`]), judging a run without truth
//! ([`consistency`]), and a run on laser ranges against the target's predictions ([`against_cpf`]).

pub mod against_cpf;
pub mod births;
pub mod components;
pub mod consistency;
pub mod exactness;
pub mod metrics;
pub mod observed;
pub mod score;
