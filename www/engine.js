// The main thread's handle on the worker (worker.js): promise-based calls, and recovery
// from a panic in the Rust code by replacing the worker and reloading the last good mesh.

/** The worker: worker.js beside this module, or, in the one-file page (`make single`,
 * scripts/single.mjs), the worker inlined in the page (a script element of type
 * text/plain, which does not run) started from a blob of its text, as a classic worker
 * (bundled: a module worker does not start from a blob in a page opened from file://). */
let inlinedWorker = null;
function startWorker() {
  const inlined = document.getElementById('worker-source');
  if (!inlined) return new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  inlinedWorker ??= URL.createObjectURL(new Blob([inlined.textContent], { type: 'text/javascript' }));
  return new Worker(inlinedWorker);
}

export class Engine {
  constructor(onPanic) {
    this.onPanic = onPanic;
    this.nextId = 1;
    this.pending = new Map();
    this.memory = 0; // bytes of the wasm memory at the last answer
    this.peakMemory = 0; // the most seen (wasm memory never shrinks; a restart starts again)
    this.gate = Promise.resolve(); // calls wait behind a reload after a restart
    this.spawn();
  }

  spawn() {
    this.worker = startWorker();
    this.worker.onmessage = (ev) => {
      const received = performance.timeOrigin + performance.now();
      const { id, ok, result, error, panic, t, memory } = ev.data;
      if (memory) {
        this.memory = memory;
        this.peakMemory = Math.max(this.peakMemory, memory);
      }
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      if (t) p.timing.worker = t;
      p.timing.received = received;
      if (ok) p.resolve(p.timed ? { result, timing: p.timing } : result);
      else {
        const err = new Error(error);
        err.panic = Boolean(panic);
        p.reject(err);
        if (panic) this.onPanic(err);
      }
    };
    this.worker.onerror = (ev) => {
      ev.preventDefault();
      const err = new Error(`the engine failed to start: ${ev.message || 'unknown error'}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
  }

  /** Calls a worker command; resolves with its result, rejects with the core's message. */
  call(cmd, ...args) {
    return this.gate.then(() => this.raw(cmd, args, false));
  }

  /**
   * As `call`, resolving with `{ result, timing }`: `timing` has `sent` and `received`
   * (the page's clock) and `worker: { start, end }` (the worker's), all in ms since the
   * epoch, so `received − worker.end` is the time the answer took to arrive.
   */
  timed(cmd, ...args) {
    return this.gate.then(() => this.raw(cmd, args, true));
  }

  raw(cmd, args, timed = false) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      const timing = { sent: performance.timeOrigin + performance.now() };
      this.pending.set(id, { resolve, reject, timed, timing });
      const transfer = args.filter((a) => a instanceof ArrayBuffer);
      this.worker.postMessage({ id, cmd, args }, transfer);
    });
  }

  /**
   * A fresh worker: after a panic the old handle cannot be trusted. `reload(call)` runs
   * first on the new worker (to load the last good mesh); every other call waits for it.
   */
  restart(reload) {
    this.worker.terminate();
    const err = new Error('the engine was restarted');
    for (const p of this.pending.values()) p.reject(err);
    this.pending.clear();
    this.spawn();
    const run = reload((cmd, ...args) => this.raw(cmd, args));
    this.gate = run.catch(() => {});
    return run;
  }
}
