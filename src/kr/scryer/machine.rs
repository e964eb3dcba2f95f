//! The thread that owns an agent's scryer machines. A scryer `Machine` cannot move between
//! threads, while agents do (the worker pool hands them out per round), so each scryer agent
//! gets one thread holding its machines; its engine sends requests and waits for the reply.
//! A panic inside scryer is caught here and becomes an error of that agent; the machine it
//! happened in is rebuilt for the next request.

use super::text;
use crate::kr::KrError;
use crate::term::Term;
use crossbeam_channel::{bounded, Receiver, RecvTimeoutError, Sender};
use scryer_prolog::{LeafAnswer, Machine, MachineBuilder, StreamConfig};
use std::cell::{Cell, RefCell};
use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::rc::Rc;
use std::thread::JoinHandle;
use std::time::Instant;

/// One request: bring the facts of machine `world` up to date, then run `goal`.
pub struct Request {
    /// Which machine: one per kind of view (beliefs, goals, other bases).
    pub world: usize,
    /// Start this machine afresh (memory of retracted clauses is given back).
    pub rebuild: bool,
    /// Ground facts to retract, then facts to assert.
    pub retract: Vec<Term>,
    pub assert: Vec<Term>,
    /// The answer template and the (rewritten) goal.
    pub template: Term,
    pub goal: Term,
    /// 1: the first answer only; 0: every answer.
    pub cap: u8,
    /// The inference budget.
    pub inferences: u64,
}

/// What a request gives back: the instances of the template and the text written.
pub type Reply = Result<(Vec<Term>, String), KrError>;

/// The handle of a machine thread.
pub struct Worker {
    tx: Option<Sender<Request>>,
    rx: Receiver<Reply>,
    join: Option<JoinHandle<()>>,
    /// A request outlived its time: the thread is left to finish on its own.
    stuck: Cell<bool>,
}

/// Number of machines (kinds of view) a worker keeps.
pub const WORLDS: usize = 3;

impl Worker {
    /// Starts the thread; `program` is the prelude plus the knowledge as scryer text.
    pub fn start(program: String) -> Result<Worker, KrError> {
        let (tx, rx_req) = bounded::<Request>(1);
        let (tx_rep, rx) = bounded::<Reply>(1);
        let join = std::thread::Builder::new()
            .name("scryer".into())
            .stack_size(64 << 20)
            .spawn(move || serve(program, rx_req, tx_rep))
            .map_err(|e| fault(&format!("cannot start the scryer thread: {e}")))?;
        Ok(Worker {
            tx: Some(tx),
            rx,
            join: Some(join),
            stuck: Cell::new(false),
        })
    }

    /// Sends a request and waits for its reply until `until`. A request still running then
    /// (work scryer's inference count does not bound, such as unifying long lists again and
    /// again) is an interrupted query; the worker is then [`stuck`](Worker::stuck).
    pub fn ask(&self, r: Request, until: Instant) -> Reply {
        let tx = self
            .tx
            .as_ref()
            .ok_or_else(|| fault("scryer thread stopped"))?;
        tx.send(r).map_err(|_| fault("the scryer thread stopped"))?;
        match self.rx.recv_deadline(until) {
            Ok(reply) => reply,
            Err(RecvTimeoutError::Timeout) => {
                self.stuck.set(true);
                Err(KrError::Interrupted {
                    predicate: "scryer query".into(),
                })
            }
            Err(RecvTimeoutError::Disconnected) => Err(fault("the scryer thread stopped")),
        }
    }

    /// True when a request outlived its time: the worker must be replaced.
    pub fn stuck(&self) -> bool {
        self.stuck.get()
    }

    /// Sends no more requests: the thread ends once its current one does.
    pub fn close(&mut self) {
        self.tx = None;
    }

    /// True when the thread has ended (a closed one ends when its query does).
    pub fn finished(&self) -> bool {
        self.join.as_ref().is_none_or(|j| j.is_finished())
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.tx = None;
        if let Some(j) = self.join.take() {
            // A stuck thread cannot be stopped (scryer has no per-machine interrupt): it is
            // detached, ends when its query does, and its reply goes nowhere.
            if !self.stuck.get() {
                let _ = j.join();
            }
        }
    }
}

/// An error term `error(system_error(Message), _)`.
pub fn fault(message: &str) -> KrError {
    KrError::iso(
        Term::compound("system_error", vec![Term::string(message)]),
        None,
    )
}

/// True for errors of the engine itself (not of the query): the machine is then rebuilt.
pub fn is_fault(e: &KrError) -> bool {
    matches!(e, KrError::Iso(t) if t.args().first().is_some_and(|f| f.is_functor(crate::term::Sym::intern("system_error"), 1)))
}

/// A machine with the program loaded, and the output it wrote.
struct World {
    machine: Machine,
    output: Rc<RefCell<Vec<u8>>>,
}

fn build(program: &str) -> Result<World, KrError> {
    catch_unwind(AssertUnwindSafe(|| {
        let output = Rc::new(RefCell::new(Vec::new()));
        let sink = output.clone();
        let (_input, streams) = StreamConfig::from_callbacks(
            Some(Box::new(move |c: &mut Cursor<Vec<u8>>| {
                sink.borrow_mut().extend_from_slice(c.get_ref());
                c.get_mut().clear();
                c.set_position(0);
            }) as Box<dyn FnMut(&mut Cursor<Vec<u8>>)>),
            None,
        );
        let mut machine = MachineBuilder::default().with_streams(streams).build();
        machine.load_module_string("goal_agent", program.to_string());
        World { machine, output }
    }))
    .map_err(|_| fault("scryer panicked while loading the knowledge"))
    .and_then(|mut w| {
        // Loading writes warnings (discarded) and errors (which leave the machine unusable).
        solve(&mut w.machine, &Term::atom("flush_output"))?;
        let said =
            String::from_utf8_lossy(&std::mem::take(&mut *w.output.borrow_mut())).into_owned();
        match said.lines().find(|l| l.contains("error")) {
            Some(line) => Err(fault(&format!("scryer cannot load the knowledge: {line}"))),
            None => Ok(w),
        }
    })
}

fn serve(program: String, rx: Receiver<Request>, tx: Sender<Reply>) {
    let mut worlds: Vec<Option<World>> = (0..WORLDS).map(|_| None).collect();
    while let Ok(r) = rx.recv() {
        let w = r.world.min(WORLDS - 1);
        if r.rebuild {
            worlds[w] = None;
        }
        let reply = match &mut worlds[w] {
            Some(world) => run(world, &r),
            slot => match build(&program) {
                Ok(world) => run(slot.insert(world), &r),
                Err(e) => Err(e),
            },
        };
        if reply.as_ref().is_err_and(is_fault) {
            // After a panic the machine's state is unknown: start it afresh next time.
            worlds[w] = None;
        }
        if tx.send(reply).is_err() {
            break;
        }
    }
}

fn run(world: &mut World, r: &Request) -> Reply {
    if !r.retract.is_empty() || !r.assert.is_empty() {
        let sync = Term::compound(
            "$goal_sync",
            vec![Term::list(r.retract.clone()), Term::list(r.assert.clone())],
        );
        match solve(&mut world.machine, &sync)? {
            Answer::Bound => {}
            Answer::Error(e) => return Err(KrError::Iso(e)),
            Answer::Failed => return Err(fault("updating the facts failed")),
        }
    }
    // Run under `\+ \+`: scryer's Rust API then reads back no binding (it reads lists of
    // characters wrong); the answer comes back as text after a marker on the output.
    let q = Term::compound(
        "\\+",
        vec![Term::compound(
            "\\+",
            vec![Term::compound(
                "$goal_run",
                vec![
                    r.template.clone(),
                    r.goal.clone(),
                    Term::Int(r.cap as i64),
                    Term::Int(r.inferences.min(i64::MAX as u64) as i64),
                    Term::var("_"),
                ],
            )],
        )],
    );
    match solve(&mut world.machine, &q)? {
        Answer::Bound => {}
        Answer::Error(e) => return Err(KrError::Iso(e)),
        Answer::Failed => return Err(fault("the query wrapper failed")),
    }
    let said =
        String::from_utf8_lossy(&std::mem::take(&mut *world.output.borrow_mut())).into_owned();
    let Some((output, text)) = said.rsplit_once(ANSWER_MARK) else {
        return Err(fault("scryer gave no answer"));
    };
    let result = read_answer(text)?;
    if result.is_functor(crate::term::Sym::intern("budget"), 0) {
        return Err(KrError::Budget {
            predicate: "scryer query".into(),
            limit: r.inferences,
        });
    }
    let inner = result.args().first().cloned().unwrap_or(Term::nil());
    if result.is_functor(crate::term::Sym::intern("err"), 1) {
        return Err(if inner.is_functor(crate::term::Sym::intern("error"), 2) {
            KrError::Iso(inner)
        } else {
            KrError::Uncaught(inner)
        });
    }
    match inner.list_items() {
        Some(items) => Ok((items, output.to_string())),
        None => Err(fault("unexpected answer from scryer")),
    }
}

/// What `'$goal_run'` writes before the answer.
const ANSWER_MARK: &str = "\u{1}goal-answer\u{1}";

/// Reads the answer `'$goal_run'` wrote (`ok(Answers)`, `err(E)` or `budget`).
fn read_answer(text: &str) -> Result<Term, KrError> {
    crate::syntax::prolog::Reader::new("scryer answer")
        .term(text.trim(), 0)
        .map(|t| t.term)
        .map_err(|d| {
            if d.message.contains("levels deep") {
                KrError::Resource {
                    resource: "memory",
                    predicate: "scryer answer".into(),
                    limit: crate::syntax::prolog::lexer::MAX_NESTING as u64,
                }
            } else {
                fault(&format!(
                    "cannot read scryer's answer: {} in {text}",
                    d.message
                ))
            }
        })
}

enum Answer {
    Bound,
    Error(Term),
    Failed,
}

/// Runs a query printed from a term: whether it succeeded, the error it raised, or failure.
fn solve(machine: &mut Machine, q: &Term) -> Result<Answer, KrError> {
    let text = format!("{} .", text::canonical(q));
    let run = catch_unwind(AssertUnwindSafe(|| {
        machine.run_query(text).take(2).collect::<Vec<_>>()
    }));
    let answer = run.map_err(|_| fault("scryer panicked while answering"))?;
    Ok(match answer.into_iter().next() {
        None | Some(Ok(LeafAnswer::False)) => Answer::Failed,
        Some(Ok(LeafAnswer::Exception(e))) | Some(Err(e)) => {
            Answer::Error(text::from_scryer(&e, 0)?)
        }
        Some(Ok(LeafAnswer::True)) | Some(Ok(LeafAnswer::LeafAnswer { .. })) => Answer::Bound,
    })
}
