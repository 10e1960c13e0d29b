// The main thread's handle on the worker (worker.js): promise-based calls, and recovery
// from a panic in the Rust code by replacing the worker and reloading the last good mesh.

export class Engine {
  constructor(onPanic) {
    this.onPanic = onPanic;
    this.nextId = 1;
    this.pending = new Map();
    this.gate = Promise.resolve(); // calls wait behind a reload after a restart
    this.spawn();
  }

  spawn() {
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (ev) => {
      const { id, ok, result, error, panic } = ev.data;
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      if (ok) p.resolve(result);
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
    return this.gate.then(() => this.raw(cmd, ...args));
  }

  raw(cmd, ...args) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
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
    const run = reload((cmd, ...args) => this.raw(cmd, ...args));
    this.gate = run.catch(() => {});
    return run;
  }
}
