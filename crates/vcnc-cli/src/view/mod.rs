//! `vcnc view`'s parts: the scene taken from the motion stream ([`scene`]), the self-contained
//! page around it ([`page`]) and the tiny HTTP server on 127.0.0.1 that serves it ([`serve`]).

pub(crate) mod page;
pub(crate) mod scene;
pub(crate) mod serve;
