#!/usr/bin/env python3
"""Serves a folder over HTTP on 127.0.0.1 for the browser build of softbody.

Every response carries the two headers that make the page cross-origin isolated
(Cross-Origin-Opener-Policy and Cross-Origin-Embedder-Policy): only then does the browser
give the page SharedArrayBuffer, which the threaded build needs. A host that cannot send
them still serves the one-thread build (the page picks; see index.html).

    python3 serve.py [--port 8080] [--bind 127.0.0.1] [--no-isolation] [--quiet] FOLDER
"""
import argparse
import functools
import http.server
import sys


class Handler(http.server.SimpleHTTPRequestHandler):
    isolation = True
    quiet = False

    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
        ".data": "application/octet-stream",
    }

    def end_headers(self):
        if self.isolation:
            self.send_header("Cross-Origin-Opener-Policy", "same-origin")
            self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        # A rebuilt page is picked up on reload, not served stale from the cache.
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def log_message(self, format, *args):
        if not self.quiet:
            super().log_message(format, *args)


def main():
    parser = argparse.ArgumentParser(description="Serve the browser build of softbody.")
    parser.add_argument("folder")
    parser.add_argument("--port", type=int, default=8080)
    parser.add_argument("--bind", default="127.0.0.1")
    parser.add_argument("--no-isolation", action="store_true",
                        help="leave out COOP/COEP (the page then runs on one thread)")
    parser.add_argument("--quiet", action="store_true", help="no line per request")
    args = parser.parse_args()

    Handler.isolation = not args.no_isolation
    Handler.quiet = args.quiet
    handler = functools.partial(Handler, directory=args.folder)
    try:
        server = http.server.ThreadingHTTPServer((args.bind, args.port), handler)
    except OSError as error:
        print(f"serve.py: cannot listen on {args.bind}:{args.port}: {error.strerror}", file=sys.stderr)
        return 2
    host, port = server.server_address[:2]
    print(f"serve.py: serving {args.folder} at http://{host}:{port}/ (Ctrl+C stops)", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
