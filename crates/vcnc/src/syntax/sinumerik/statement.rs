//! (to be written: SINUMERIK statements)
