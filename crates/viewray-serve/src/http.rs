//! The HTTP side: hyper's HTTP/1.1 connections on a small tokio runtime, requests
//! answered on a bounded pool of blocking threads (the renders and every other answer
//! are plain synchronous code), the render slots that bound how many renders run at
//! once, and the tickets through which a newer render stops the one it supersedes.
//!
//! A browser keeps its connections open between requests and opens several at once; an
//! idle connection costs no thread here, so none waits for another to close.
//!
//! A page's view asks for one picture after another as a slider moves, and abandons
//! each as the next is asked for; the server is not told that the connection of an
//! abandoned one closed while it renders. So each render may carry a `ticket`, `NAME.TURN` (the
//! page's name for that view and the render's turn in it): a render with a ticket stops
//! the renders of its name with an earlier turn, running (at their next tile) or waiting
//! for a slot (at once), which are answered 409; one that arrives after a later turn of
//! its name (requests overtake each other on their way in) is answered 409 at once.

use std::collections::HashMap;
use std::convert::Infallible;
use std::io;
use std::net::{SocketAddr, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::{Duration, Instant};

use http_body_util::Full;
use hyper::body::{Bytes, Incoming};
use hyper::header::{HeaderName, HeaderValue};
use hyper::service::service_fn;
use hyper::{Method, Request, Response, StatusCode};
use hyper_util::rt::TokioIo;
use hyper_util::server::graceful::GracefulShutdown;
use tokio::sync::Notify;

use crate::api::{self, RenderRequest, Reply, Route};
use crate::params::Ticket;
use crate::slide;
use crate::{Limits, ServedScene};

/// How a server answers: its limits and how much it does at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ServeOptions {
    /// How much one request may ask for.
    pub limits: Limits,
    /// How many requests are answered at once (each by a thread of its own; more wait
    /// their turn, their connections open).
    pub workers: usize,
    /// How many renders run at once (each uses every core through the render's own
    /// threads, so one or two keep the machine busy).
    pub render_slots: usize,
    /// How long a render request waits for a free slot before it is refused with 503.
    pub slot_wait: Duration,
    /// How many render requests may wait for a slot at once; more are refused with 503
    /// at once, so that workers stay free for the cheap requests.
    pub max_waiting: usize,
}

impl Default for ServeOptions {
    fn default() -> Self {
        Self {
            limits: Limits::default(),
            workers: 16,
            render_slots: 2,
            slot_wait: Duration::from_secs(3),
            max_waiting: 8,
        }
    }
}

/// A running HTTP server for one [`ServedScene`], bound to its address; [`Server::run`]
/// answers requests until a [`Stopper`] stops it.
pub struct Server {
    listener: std::net::TcpListener,
    shared: Arc<Shared>,
    address: SocketAddr,
}

/// What every worker reads.
struct Shared {
    served: ServedScene,
    options: ServeOptions,
    slots: Slots,
    tickets: Tickets,
    counts: Counts,
    /// Told when the server is to stop (a permit kept if nobody waits yet).
    stop: Notify,
}

/// How many renders ended each way since the server started (`/api/status`).
#[derive(Default)]
struct Counts {
    /// Renders answered with their picture.
    rendered: AtomicU64,
    /// Renders given up for a newer one with their ticket (running or waiting).
    superseded: AtomicU64,
    /// Renders refused for want of a free slot (503).
    busy: AtomicU64,
}

/// Stops a running [`Server`] from another thread (a Ctrl-C handler): requests being
/// answered are finished, then [`Server::run`] returns.
#[derive(Clone)]
pub struct Stopper {
    shared: Arc<Shared>,
}

impl Stopper {
    /// Asks the server to stop.
    pub fn stop(&self) {
        self.shared.stop.notify_one();
    }
}

impl Server {
    /// Binds to `address` (port 0: a free port) to serve `served`.
    ///
    /// # Errors
    /// The address cannot be resolved or bound (in use, not this machine's).
    pub fn bind(
        served: ServedScene,
        address: impl ToSocketAddrs,
        options: ServeOptions,
    ) -> io::Result<Server> {
        let address = address.to_socket_addrs()?.next().ok_or_else(|| {
            io::Error::new(io::ErrorKind::InvalidInput, "the address names no host")
        })?;
        let listener = std::net::TcpListener::bind(address)?;
        listener.set_nonblocking(true)?;
        let address = listener.local_addr()?;
        let options = ServeOptions {
            workers: options.workers.max(1),
            render_slots: options.render_slots.max(1),
            ..options
        };
        Ok(Server {
            listener,
            shared: Arc::new(Shared {
                served,
                slots: Slots::new(options.render_slots),
                tickets: Tickets::default(),
                counts: Counts::default(),
                options,
                stop: Notify::new(),
            }),
            address,
        })
    }

    /// The address it listens on (with the port chosen when 0 was asked for).
    pub fn address(&self) -> SocketAddr {
        self.address
    }

    /// The page's URL, `http://HOST:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.address)
    }

    /// A handle that stops [`Server::run`].
    pub fn stopper(&self) -> Stopper {
        Stopper {
            shared: Arc::clone(&self.shared),
        }
    }

    /// Answers requests, [`ServeOptions::workers`] at once, until stopped; then stops
    /// listening, lets the requests being answered finish, closes the idle connections
    /// and returns.
    ///
    /// # Errors
    /// The runtime or the listener could not be set up (no threads, no sockets left).
    pub fn run(self) -> io::Result<()> {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .max_blocking_threads(self.shared.options.workers)
            .thread_name("viewray-serve")
            .enable_io()
            .build()?;
        runtime.block_on(serve(self.listener, self.shared))
    }
}

/// Accepts connections until told to stop, each served by hyper on the runtime.
async fn serve(listener: std::net::TcpListener, shared: Arc<Shared>) -> io::Result<()> {
    let listener = tokio::net::TcpListener::from_std(listener)?;
    let graceful = GracefulShutdown::new();
    loop {
        tokio::select! {
            accepted = listener.accept() => {
                // A connection that failed before it was accepted is the client's loss.
                let Ok((stream, _)) = accepted else { continue };
                let shared = Arc::clone(&shared);
                let service = service_fn(move |request| {
                    let shared = Arc::clone(&shared);
                    async move { Ok::<_, Infallible>(respond(shared, request).await) }
                });
                let connection = hyper::server::conn::http1::Builder::new()
                    .serve_connection(TokioIo::new(stream), service);
                let connection = graceful.watch(connection);
                tokio::spawn(async move {
                    // A client that went away cannot be told anything.
                    let _ = connection.await;
                });
            }
            () = shared.stop.notified() => break,
        }
    }
    drop(listener);
    graceful.shutdown().await;
    Ok(())
}

/// Answers one request on a blocking thread (renders take a while; the rest is quick).
async fn respond(shared: Arc<Shared>, request: Request<Incoming>) -> Response<Full<Bytes>> {
    let method = request.method().clone();
    let target = request
        .uri()
        .path_and_query()
        .map_or_else(|| "/".to_owned(), |target| target.as_str().to_owned());
    let reply = tokio::task::spawn_blocking(move || answer(&shared, &method, &target))
        .await
        .unwrap_or_else(|_| Reply::error(500, "the server failed answering this request"));
    response(reply)
}

/// Answers one request: `method` on `target` (a path with its query).
fn answer(shared: &Shared, method: &Method, target: &str) -> Reply {
    if *method == Method::GET || *method == Method::HEAD {
        let (path, query) = target.split_once('?').unwrap_or((target, ""));
        if path == "/api/status" {
            status(shared)
        } else {
            match api::route(&shared.served, &shared.options.limits, path, query) {
                Route::Now(reply) => reply,
                Route::Render(render) => render_in_slot(shared, &render),
                Route::Slide(request) => match shared.slots.acquire(
                    shared.options.slot_wait,
                    shared.options.max_waiting,
                    &AtomicBool::new(false),
                ) {
                    Ok(_slot) => slide::slide(&shared.served, &request),
                    Err(_) => busy(),
                },
            }
        }
    } else {
        Reply::error(
            405,
            &format!("method {method} is not allowed: the playground answers GET"),
        )
    }
}

/// The HTTP response for `reply`: a Content-Length rather than chunks, whatever the
/// size (bodies are in memory); hyper sends no body to a HEAD request.
fn response(reply: Reply) -> Response<Full<Bytes>> {
    let mut response = Response::new(Full::new(Bytes::from(reply.body)));
    *response.status_mut() =
        StatusCode::from_u16(reply.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let headers = response.headers_mut();
    let mut add = |name: &'static str, value: &str| {
        if let Ok(value) = HeaderValue::from_str(value) {
            headers.insert(HeaderName::from_static(name), value);
        }
    };
    add("content-type", reply.content_type);
    add("cache-control", "no-store");
    add("x-content-type-options", "nosniff");
    if let Some(timing) = &reply.timing {
        add("server-timing", timing);
    }
    match reply.status {
        405 => add("allow", "GET, HEAD"),
        503 => add("retry-after", "1"),
        _ => {}
    }
    response
}

/// Renders `render` in a free slot: first stops the render its ticket supersedes, then
/// waits for a slot (unless superseded in turn meanwhile), renders, and counts how it
/// ended.
fn render_in_slot(shared: &Shared, render: &RenderRequest) -> Reply {
    let ticket = render.ticket.as_ref();
    let cancelled = match ticket {
        Some(ticket) => shared.tickets.take(ticket, &shared.slots),
        None => Arc::new(AtomicBool::new(false)),
    };
    let reply = match shared.slots.acquire(
        shared.options.slot_wait,
        shared.options.max_waiting,
        &cancelled,
    ) {
        Ok(_slot) => api::render(&shared.served, &render.view, &cancelled),
        Err(Refusal::Busy) => busy(),
        Err(Refusal::Superseded) => api::superseded(),
    };
    if let Some(ticket) = ticket {
        shared.tickets.release(&ticket.name, &cancelled);
    }
    let count = match reply.status {
        200 => &shared.counts.rendered,
        api::SUPERSEDED => &shared.counts.superseded,
        503 => &shared.counts.busy,
        _ => return reply,
    };
    count.fetch_add(1, Ordering::Relaxed);
    reply
}

/// `/api/status`: the renders running and waiting now, and how many ended each way.
fn status(shared: &Shared) -> Reply {
    let (running, waiting) = shared.slots.now();
    let count = |c: &AtomicU64| c.load(Ordering::Relaxed);
    let counts = &shared.counts;
    let mut body = serde_json::json!({
        "renders": {
            "running": running,
            "waiting": waiting,
            "rendered": count(&counts.rendered),
            "superseded": count(&counts.superseded),
            "busy": count(&counts.busy),
        }
    })
    .to_string();
    body.push('\n');
    Reply::ok("application/json", body)
}

/// The answer to a render that found no free slot in time.
fn busy() -> Reply {
    Reply::error(
        503,
        "the server is busy rendering for others: try again in a moment",
    )
}

/// The renders with a ticket, running or waiting: for each ticket's name, the turn of
/// the latest and the flag that stops it (an entry lives as long as its render, so there
/// are at most as many as workers).
#[derive(Default)]
struct Tickets(Mutex<HashMap<String, (u64, Arc<AtomicBool>)>>);

impl Tickets {
    /// A render with `ticket` comes: stops the one of its name with an earlier turn
    /// (waking it if it waits for a slot) and returns the flag that stops this one; set
    /// already if a later turn came first.
    fn take(&self, ticket: &Ticket, slots: &Slots) -> Arc<AtomicBool> {
        let flag = Arc::new(AtomicBool::new(false));
        let mut tickets = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        if tickets
            .get(&ticket.name)
            .is_some_and(|&(turn, _)| turn > ticket.turn)
        {
            flag.store(true, Ordering::SeqCst);
            return flag;
        }
        let before = tickets.insert(ticket.name.clone(), (ticket.turn, Arc::clone(&flag)));
        drop(tickets);
        if let Some((_, before)) = before {
            before.store(true, Ordering::SeqCst);
            slots.wake_all();
        }
        flag
    }

    /// The render of ticket `name` with `flag` ended: its entry goes, unless a later
    /// turn took the name meanwhile.
    fn release(&self, name: &str, flag: &Arc<AtomicBool>) {
        let mut tickets = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        if tickets.get(name).is_some_and(|(_, f)| Arc::ptr_eq(f, flag)) {
            tickets.remove(name);
        }
    }
}

/// Why a render got no slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Refusal {
    /// None came free in time, or too many were waiting.
    Busy,
    /// A newer render with its ticket came while it waited.
    Superseded,
}

/// A counting semaphore for renders, with a bound on how many may wait.
struct Slots {
    state: Mutex<SlotState>,
    freed: Condvar,
    capacity: usize,
}

#[derive(Default)]
struct SlotState {
    busy: usize,
    waiting: usize,
}

/// A render slot, given back when dropped.
struct Slot<'a>(&'a Slots);

impl Drop for Slot<'_> {
    fn drop(&mut self) {
        let mut state = self.0.state.lock().unwrap_or_else(PoisonError::into_inner);
        state.busy -= 1;
        drop(state);
        self.0.freed.notify_one();
    }
}

impl Slots {
    fn new(capacity: usize) -> Slots {
        Slots {
            state: Mutex::new(SlotState::default()),
            freed: Condvar::new(),
            capacity,
        }
    }

    /// A free slot, waiting up to `wait` for one; refused when none came free in time,
    /// when `max_waiting` requests are waiting already, or when `cancelled` is set
    /// (before or while it waits: [`Slots::wake_all`] wakes it).
    fn acquire(
        &self,
        wait: Duration,
        max_waiting: usize,
        cancelled: &AtomicBool,
    ) -> Result<Slot<'_>, Refusal> {
        let deadline = Instant::now() + wait;
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if cancelled.load(Ordering::SeqCst) {
            return Err(Refusal::Superseded);
        }
        if state.busy < self.capacity {
            state.busy += 1;
            return Ok(Slot(self));
        }
        if state.waiting >= max_waiting {
            return Err(Refusal::Busy);
        }
        state.waiting += 1;
        while state.busy >= self.capacity {
            if cancelled.load(Ordering::SeqCst) {
                state.waiting -= 1;
                return Err(Refusal::Superseded);
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                state.waiting -= 1;
                return Err(Refusal::Busy);
            }
            state = self
                .freed
                .wait_timeout(state, left)
                .unwrap_or_else(PoisonError::into_inner)
                .0;
        }
        state.waiting -= 1;
        state.busy += 1;
        Ok(Slot(self))
    }

    /// Wakes every request waiting for a slot, to look at its flag (taking the lock
    /// first, so that one between its look and its wait is not missed).
    fn wake_all(&self) {
        drop(self.state.lock().unwrap_or_else(PoisonError::into_inner));
        self.freed.notify_all();
    }

    /// The renders running and waiting now.
    fn now(&self) -> (usize, usize) {
        let state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        (state.busy, state.waiting)
    }
}

#[cfg(test)]
mod tests {
    use std::thread;

    use super::*;

    #[test]
    fn slots_bound_the_renders_and_the_waiting() {
        let slots = Slots::new(2);
        let go = AtomicBool::new(false);
        let a = slots.acquire(Duration::ZERO, 0, &go).expect("a free slot");
        let b = slots
            .acquire(Duration::ZERO, 0, &go)
            .expect("a second free slot");
        // Full, and nobody may wait.
        assert_eq!(
            slots.acquire(Duration::from_millis(50), 0, &go).err(),
            Some(Refusal::Busy)
        );
        // Full, waiting allowed, but nothing comes free in time.
        assert_eq!(
            slots.acquire(Duration::from_millis(20), 1, &go).err(),
            Some(Refusal::Busy)
        );
        // A slot given back goes to the one waiting.
        thread::scope(|scope| {
            let waiter = scope.spawn(|| slots.acquire(Duration::from_secs(10), 1, &go).is_ok());
            thread::sleep(Duration::from_millis(20));
            drop(a);
            assert!(waiter.join().unwrap());
        });
        drop(b);
        let state = slots.state.lock().unwrap();
        assert_eq!((state.busy, state.waiting), (0, 0));
    }

    fn ticket(turn: u64) -> Ticket {
        Ticket {
            name: "view".to_owned(),
            turn,
        }
    }

    #[test]
    fn a_later_turn_stops_the_render_waiting_for_a_slot() {
        let slots = Slots::new(1);
        let tickets = Tickets::default();
        let held = slots
            .acquire(Duration::ZERO, 0, &AtomicBool::new(false))
            .expect("a free slot");
        let first = tickets.take(&ticket(1), &slots);
        thread::scope(|scope| {
            // Waits as long as it takes: only the later turn can end its wait.
            let waiter = scope.spawn(|| {
                slots
                    .acquire(Duration::from_secs(3600), 1, &first)
                    .map(drop)
            });
            while slots.now().1 == 0 {
                thread::yield_now();
            }
            let second = tickets.take(&ticket(2), &slots);
            assert_eq!(waiter.join().unwrap(), Err(Refusal::Superseded));
            assert!(!second.load(Ordering::SeqCst));
            // An earlier turn arriving late is superseded at once, and takes nothing.
            let late = tickets.take(&ticket(0), &slots);
            assert!(late.load(Ordering::SeqCst) && !second.load(Ordering::SeqCst));
            tickets.release("view", &late);
            // The first's end leaves the later entry; the later's end removes it.
            tickets.release("view", &first);
            assert_eq!(tickets.0.lock().unwrap().len(), 1);
            tickets.release("view", &second);
            assert!(tickets.0.lock().unwrap().is_empty());
        });
        drop(held);
        assert_eq!(slots.now(), (0, 0));
    }
}
