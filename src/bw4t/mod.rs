//! The Blocks World for Teams environment: maps, world, navigation, percepts and actions.
