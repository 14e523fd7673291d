//! The HTTP side: tiny_http's listener, a fixed pool of workers that answer requests,
//! and the render slots that bound how many renders run at once.

use std::io;
use std::net::{SocketAddr, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::thread;
use std::time::{Duration, Instant};

use tiny_http::{Header, Method, Request, Response};

use crate::api::{self, Reply, Route};
use crate::slide;
use crate::{Limits, ServedScene};

/// How a server answers: its limits and how much it does at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ServeOptions {
    /// How much one request may ask for.
    pub limits: Limits,
    /// How many requests are answered at once (each by a thread of its own).
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
    http: Arc<tiny_http::Server>,
    shared: Arc<Shared>,
    address: SocketAddr,
}

/// What every worker reads.
struct Shared {
    served: ServedScene,
    options: ServeOptions,
    slots: Slots,
    stopping: AtomicBool,
}

/// Stops a running [`Server`] from another thread (a Ctrl-C handler): requests being
/// answered are finished, then [`Server::run`] returns.
#[derive(Clone)]
pub struct Stopper {
    http: Arc<tiny_http::Server>,
    shared: Arc<Shared>,
}

impl Stopper {
    /// Asks the server to stop.
    pub fn stop(&self) {
        self.shared.stopping.store(true, Ordering::SeqCst);
        // Each unblock wakes one worker waiting for a request.
        for _ in 0..self.shared.options.workers {
            self.http.unblock();
        }
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
        let http = tiny_http::Server::http(address).map_err(io::Error::other)?;
        let address = http
            .server_addr()
            .to_ip()
            .ok_or_else(|| io::Error::other("the server is not on an IP address"))?;
        let options = ServeOptions {
            workers: options.workers.max(1),
            render_slots: options.render_slots.max(1),
            ..options
        };
        Ok(Server {
            http: Arc::new(http),
            shared: Arc::new(Shared {
                served,
                slots: Slots::new(options.render_slots),
                options,
                stopping: AtomicBool::new(false),
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
            http: Arc::clone(&self.http),
            shared: Arc::clone(&self.shared),
        }
    }

    /// Answers requests with [`ServeOptions::workers`] threads until stopped; returns
    /// when every worker has finished its request. The listening socket closes when the
    /// server is dropped.
    pub fn run(self) {
        let workers: Vec<_> = (0..self.shared.options.workers)
            .map(|k| {
                let http = Arc::clone(&self.http);
                let shared = Arc::clone(&self.shared);
                thread::Builder::new()
                    .name(format!("viewray-serve-{k}"))
                    .spawn(move || work(&http, &shared))
            })
            .collect();
        for worker in workers.into_iter().flatten() {
            let _ = worker.join();
        }
    }
}

/// A worker: takes requests and answers them until the server stops.
fn work(http: &tiny_http::Server, shared: &Shared) {
    while !shared.stopping.load(Ordering::SeqCst) {
        match http.recv() {
            Ok(request) => answer(shared, request),
            // Unblocked by a stop, or the listener failed: either way, stop.
            Err(_) => break,
        }
    }
}

/// Answers one request.
fn answer(shared: &Shared, request: Request) {
    let reply = if matches!(request.method(), Method::Get | Method::Head) {
        let url = request.url();
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        match api::route(&shared.served, &shared.options.limits, path, query) {
            Route::Now(reply) => reply,
            Route::Render(view) => match shared
                .slots
                .acquire(shared.options.slot_wait, shared.options.max_waiting)
            {
                Some(_slot) => api::render(&shared.served, &view),
                None => busy(),
            },
            Route::Slide(request) => match shared
                .slots
                .acquire(shared.options.slot_wait, shared.options.max_waiting)
            {
                Some(_slot) => slide::slide(&shared.served, &request),
                None => busy(),
            },
        }
    } else {
        Reply::error(
            405,
            &format!(
                "method {} is not allowed: the playground answers GET",
                request.method()
            ),
        )
    };
    // A Content-Length rather than chunks, whatever the size: bodies are in memory.
    // (tiny_http sends no body to a HEAD request.)
    let mut response = Response::from_data(reply.body)
        .with_chunked_threshold(usize::MAX)
        .with_status_code(reply.status)
        .with_header(header("Content-Type", reply.content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"));
    if let Some(timing) = &reply.timing {
        response = response.with_header(header("Server-Timing", timing));
    }
    match reply.status {
        405 => response = response.with_header(header("Allow", "GET, HEAD")),
        503 => response = response.with_header(header("Retry-After", "1")),
        _ => {}
    }
    // A client that went away cannot be told anything.
    let _ = request.respond(response);
}

/// The answer to a render that found no free slot in time.
fn busy() -> Reply {
    Reply::error(
        503,
        "the server is busy rendering for others: try again in a moment",
    )
}

/// A header from ASCII name and value (all of ours are).
fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes())
        .unwrap_or_else(|()| Header::from_bytes(&b"X-Invalid"[..], &b"1"[..]).expect("ASCII"))
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

    /// A free slot, waiting up to `wait` for one; `None` when none came free in time or
    /// `max_waiting` requests are waiting already.
    fn acquire(&self, wait: Duration, max_waiting: usize) -> Option<Slot<'_>> {
        let deadline = Instant::now() + wait;
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if state.busy < self.capacity {
            state.busy += 1;
            return Some(Slot(self));
        }
        if state.waiting >= max_waiting {
            return None;
        }
        state.waiting += 1;
        while state.busy >= self.capacity {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                state.waiting -= 1;
                return None;
            }
            state = self
                .freed
                .wait_timeout(state, left)
                .unwrap_or_else(PoisonError::into_inner)
                .0;
        }
        state.waiting -= 1;
        state.busy += 1;
        Some(Slot(self))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_bound_the_renders_and_the_waiting() {
        let slots = Slots::new(2);
        let a = slots.acquire(Duration::ZERO, 0).expect("a free slot");
        let b = slots
            .acquire(Duration::ZERO, 0)
            .expect("a second free slot");
        // Full, and nobody may wait.
        assert!(slots.acquire(Duration::from_millis(50), 0).is_none());
        // Full, waiting allowed, but nothing comes free in time.
        assert!(slots.acquire(Duration::from_millis(20), 1).is_none());
        // A slot given back goes to the one waiting.
        thread::scope(|scope| {
            let waiter = scope.spawn(|| slots.acquire(Duration::from_secs(10), 1).is_some());
            thread::sleep(Duration::from_millis(20));
            drop(a);
            assert!(waiter.join().unwrap());
        });
        drop(b);
        let state = slots.state.lock().unwrap();
        assert_eq!((state.busy, state.waiting), (0, 0));
    }
}
