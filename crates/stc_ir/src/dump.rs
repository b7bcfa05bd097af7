//! Text dump of the IR (stub, filled in next).
