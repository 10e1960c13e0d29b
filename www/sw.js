// The service worker: the page works offline after its first visit. On install it keeps
// every file of the site (the list and the build's version in pkg/site.js, written by
// `make site`) in a cache named by the version; it answers the site's requests from that
// cache, and the network only for what the cache does not hold. A new build changes
// pkg/site.js, so the browser installs the new worker, which fills its own cache and,
// once it takes over, deletes the caches of older builds.
importScripts('pkg/site.js');

const CACHE = `smoothlab-${self.SITE.version}`;

self.addEventListener('install', (ev) => {
  ev.waitUntil(
    caches.open(CACHE)
      .then((cache) => cache.addAll(self.SITE.files.map((f) => new Request(f, { cache: 'reload' }))))
      .then(() => self.skipWaiting()),
  );
});

self.addEventListener('activate', (ev) => {
  ev.waitUntil(
    caches.keys()
      .then((keys) => Promise.all(keys.filter((k) => k.startsWith('smoothlab-') && k !== CACHE).map((k) => caches.delete(k))))
      .then(() => self.clients.claim()),
  );
});

self.addEventListener('fetch', (ev) => {
  const req = ev.request;
  if (req.method !== 'GET' || new URL(req.url).origin !== self.location.origin) return;
  // a page's address differs by its query (?embed=1) and hash: the one page answers them all
  ev.respondWith(
    caches.open(CACHE)
      .then((cache) => cache.match(req, { ignoreSearch: req.mode === 'navigate' }))
      .then((hit) => hit || fetch(req)),
  );
});
