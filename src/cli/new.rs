//! `goal new NAME [--template bw4t|blocks|empty] [--generation 2014|modular|course]`: a ready
//! project (a `.mas2g`, agent files, a `.test2g` and a README) from files embedded in the
//! binary: the shipped agents where one fits (`agents/`), `templates/` for the others.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// What the project does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Template {
    /// Robots in Blocks World for Teams deliver coloured blocks in sequence.
    Bw4t,
    /// A gripper builds a tower in the blocks world.
    Blocks,
    /// One agent on its own, no environment: a counter.
    Empty,
}

/// Which generation of the language the project is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Generation {
    /// Single-file `.goal` agents (GOAL 2014).
    #[value(name = "2014")]
    Y2014,
    /// Modular GOAL (2016+): `.mod2g` modules, `.act2g` action specs, `.pl` knowledge.
    Modular,
    /// MARBEL, the course language: plain-literal conditions, percept declarations.
    Course,
}

/// Arguments of `goal new`.
#[derive(clap::Args)]
pub struct Args {
    /// The directory to create (must not exist yet).
    pub name: PathBuf,
    /// What the project does.
    #[arg(long, value_enum, default_value = "bw4t")]
    pub template: Template,
    /// Which generation of GOAL to write it in.
    #[arg(long, value_enum, default_value = "2014")]
    pub generation: Generation,
}

/// One project template: its files and what the README says about them.
struct Project {
    /// The `.mas2g` file to run.
    mas: &'static str,
    /// The `.test2g` file to test.
    test: &'static str,
    /// One paragraph: what the agents do.
    what: &'static str,
    /// `(file name, contents, what it is)` for every file but the README.
    files: &'static [(&'static str, &'static str, &'static str)],
    /// More for the README (Markdown sections), or nothing.
    more: &'static str,
}

/// `(name, contents, what it is)` of project files, read from `DIR/` (relative to the crate).
macro_rules! files {
    ($dir:literal: $($file:literal => $what:literal),* $(,)?) => {
        &[$((
            $file,
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $dir, "/", $file)),
            $what,
        )),*]
    };
}

const README: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/templates/README.md"));
/// How the BW4T team template's robots split the work.
const TEAM: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/templates/bw4t/team.md"
));

const BW4T_WHAT: &str = "Robots in Blocks World for Teams (BW4T) fetch coloured blocks from the \
rooms of a map and deliver them to the drop zone in the order of the colour sequence.";

const BLOCKS_WHAT: &str =
    "A gripper in the blocks world builds the towers the agent wants, moving \
one clear block at a time.";

const EMPTY_WHAT: &str = "One agent on its own, without an environment: it counts from 0 to 100 \
and stops. A place to start from scratch.";

fn project(template: Template, generation: Generation) -> Project {
    use Generation::*;
    use Template::*;
    match (template, generation) {
        (Bw4t, Y2014) => Project {
            mas: "robot.mas2g",
            test: "robot.test2g",
            what: "One robot in Blocks World for Teams (BW4T) visits the rooms of the map one by \
                   one and delivers the blocks of the colour sequence to the drop zone, in order.",
            files: files!("agents/bw4t":
                "robot.mas2g" => "the system: the BW4T environment, map and robots, and which agent runs each robot",
                "robot.goal" => "the robot's program: knowledge, beliefs, action specs and rules",
                "robot.test2g" => "a test: the robot only heads for rooms it has not visited, and visits them all",
            ),
            more: "",
        },
        (Bw4t, Modular) => Project {
            mas: "team.mas2g",
            test: "team.test2g",
            what: BW4T_WHAT,
            files: files!("agents/bw4t/modular":
                "team.mas2g" => "the system: the BW4T environment (3 robots) and the robot agent's modules",
                "robotInit.mod2g" => "runs once: copies the map into beliefs, adopts the team's goal",
                "robotEvents.mod2g" => "runs every cycle before the decisions: percepts and messages",
                "robotMain.mod2g" => "the decisions: one action per cycle",
                "forget.mod2g" => "a module the others call: forget what a robot said it was doing",
                "robot.act2g" => "the action specs (goTo, goToBlock, pickUp, putDown)",
                "robot.pl" => "knowledge: rules about the map, routes and the team's work",
                "robotBeliefs.pl" => "the beliefs the robot starts with",
                "team.test2g" => "a test: only the colour needed now is put down, and the whole sequence is delivered",
            ),
            more: TEAM,
        },
        (Bw4t, Course) => Project {
            mas: "team.mas2g",
            test: "team.test2g",
            what: BW4T_WHAT,
            files: files!("agents/bw4t/marbel":
                "team.mas2g" => "the system: the BW4T environment (3 robots), the robot's modules and its percept declarations",
                "robotInit.mod2g" => "runs once: route lengths from every place to every room",
                "robotUpdate.mod2g" => "runs every cycle before the decisions: what the robot sees and hears",
                "robotControl.mod2g" => "the decisions: one action per cycle",
                "forget.mod2g" => "a module the others call: forget what a robot said it was doing",
                "robot.pl" => "the database: rules, and the facts the robot starts with",
                "team.test2g" => "a test: only the colour needed now is put down, and the whole sequence is delivered",
            ),
            more: TEAM,
        },
        (Blocks, Y2014) => Project {
            mas: "stacker.mas2g",
            test: "stacker.test2g",
            what: BLOCKS_WHAT,
            files: files!("agents/blocksworld":
                "stacker.mas2g" => "the system: the blocks world and its starting towers, and the stacker agent",
                "stacker.goal" => "the stacker's program",
                "stacker.test2g" => "a test: the tower c, b, a gets built",
            ),
            more: "",
        },
        (Blocks, Modular) => Project {
            mas: "stacker.mas2g",
            test: "stacker.test2g",
            what: BLOCKS_WHAT,
            files: files!("templates/blocks/modular":
                "stacker.mas2g" => "the system: the blocks world and its starting towers, and the stacker agent",
                "stackerMain.mod2g" => "the decisions: one move per cycle until no goal is left",
                "stackerEvents.mod2g" => "runs every cycle before the decisions: beliefs follow the percepts",
                "stacker.act2g" => "the action spec of move/2",
                "stacker.pl" => "knowledge: blocks, clear, tower",
                "stackerBeliefs.pl" => "the beliefs the stacker starts with",
                "stackerGoals.pl" => "the goal: the towers to build",
                "stacker.test2g" => "a test: the tower c, b, a gets built",
            ),
            more: "",
        },
        (Blocks, Course) => Project {
            mas: "stacker.mas2g",
            test: "stacker.test2g",
            what: "A gripper in the blocks world builds a tower, moving one clear block at a time.",
            files: files!("templates/blocks/course":
                "stacker.mas2g" => "the system: the blocks world and its starting towers, the stacker and its percept declaration",
                "stackerUpdate.mod2g" => "runs every cycle before the decisions: notices when the tower stands",
                "stackerControl.mod2g" => "the decisions: one move per cycle",
                "tower.pl" => "the database: rules about blocks and the wanted tower",
                "stacker.test2g" => "a test: the tower c, b, a gets built",
            ),
            more: "",
        },
        (Empty, Y2014) => Project {
            mas: "counter.mas2g",
            test: "counter.test2g",
            what: EMPTY_WHAT,
            files: files!("agents/counter":
                "counter.mas2g" => "the system: one agent, no environment",
                "counter.goal" => "the agent's program",
                "counter.test2g" => "a test: the count goes up one by one to 100",
            ),
            more: "",
        },
        (Empty, Modular) => Project {
            mas: "counter.mas2g",
            test: "counter.test2g",
            what: EMPTY_WHAT,
            files: files!("templates/empty/modular":
                "counter.mas2g" => "the system: one agent, no environment",
                "counterMain.mod2g" => "the agent's decisions",
                "counter.pl" => "knowledge",
                "counterBeliefs.pl" => "the beliefs the agent starts with",
                "counterGoals.pl" => "the goal the agent starts with",
                "counter.test2g" => "a test: the count goes up one by one to 100",
            ),
            more: "",
        },
        (Empty, Course) => Project {
            mas: "counter.mas2g",
            test: "counter.test2g",
            what: EMPTY_WHAT,
            files: files!("templates/empty/course":
                "counter.mas2g" => "the system: one agent, no environment",
                "counterControl.mod2g" => "the agent's decisions",
                "numbers.pl" => "the database: the count and where it stops",
                "counter.test2g" => "a test: the count goes up one by one to 100",
            ),
            more: "",
        },
    }
}

/// Runs `goal new`: writes the project, or says why not (exit 1).
pub fn main(args: Args) -> ExitCode {
    match create(&args) {
        Ok(p) => {
            let dir = args.name.display();
            eprintln!(
                "created {dir}: run it with `goal run {}`, test it with `goal test {}`",
                Path::new(&args.name).join(p.mas).display(),
                Path::new(&args.name).join(p.test).display(),
            );
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(super::exit::FAILURE)
        }
    }
}

/// Writes the files of the project into a new directory `args.name`.
fn create(args: &Args) -> Result<Project, String> {
    let dir = &args.name;
    let shown = dir.display();
    if dir.exists() || dir.symlink_metadata().is_ok() {
        return Err(format!(
            "`{shown}` already exists; choose another name or remove it first (goal new never overwrites)"
        ));
    }
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| !n.is_empty())
        .ok_or_else(|| format!("`{shown}` does not name a directory to create"))?;
    let p = project(args.template, args.generation);
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create `{shown}`: {e}"))?;
    let readme = readme(&p, &name, args.template, args.generation);
    let all = p
        .files
        .iter()
        .map(|(f, text, _)| (*f, *text))
        .chain([("README.md", readme.as_str())]);
    for (file, text) in all {
        let path = dir.join(file);
        std::fs::write(&path, text)
            .map_err(|e| format!("cannot write `{}`: {e}", path.display()))?;
    }
    Ok(p)
}

/// The student's README: the shared text with this project's names and files filled in.
fn readme(p: &Project, name: &str, template: Template, generation: Generation) -> String {
    let (gen, described) = match generation {
        Generation::Y2014 => ("2014", "GOAL 2014: one `.goal` file per agent"),
        Generation::Modular => (
            "modular",
            "modular GOAL (2016+): one module per `.mod2g` file, action specs in `.act2g`, Prolog in `.pl`",
        ),
        Generation::Course => (
            "course",
            "MARBEL, the course language: modules with plain Prolog conditions and a `.pl` database",
        ),
    };
    let template = match template {
        Template::Bw4t => "bw4t",
        Template::Blocks => "blocks",
        Template::Empty => "empty",
    };
    let files: Vec<String> = p
        .files
        .iter()
        .map(|(f, _, what)| format!("| `{f}` | {what} |"))
        .collect();
    README
        .replace("{{name}}", name)
        .replace(
            "{{what}}",
            &p.what.split_whitespace().collect::<Vec<_>>().join(" "),
        )
        .replace("{{generation}}", described)
        .replace("{{template}}", template)
        .replace("{{gen}}", gen)
        .replace("{{mas}}", p.mas)
        .replace("{{test}}", p.test)
        .replace("{{files}}", &files.join("\n"))
        .replace("{{more}}", p.more)
}
