"""`stochtex studio` as a server (docs/studio.md): its pages and JSON API, and that it stays safe
and serving under bad input. One server is started for the module (`stochtex studio --port 0`,
STOCHTEX_CLI from CTest) with TMPDIR set to a folder of the test, so that it can be seen to write
no file there: it decodes and encodes images in memory."""

import http.client
import io
import json
import os
import select
import signal
import socket
import struct
import subprocess
import threading
import time
import urllib.parse
import zipfile
import zlib

import pytest

STOCHTEX = os.environ["STOCHTEX_CLI"]
EXEMPLARS = os.environ["STOCHTEX_EXEMPLARS"]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def exemplar_bytes(name):
    with open(os.path.join(EXEMPLARS, name), "rb") as file:
        return file.read()


def png_size(data):
    assert data.startswith(PNG_SIGNATURE), data[:40]
    return struct.unpack(">II", data[16:24])


def grey_png(width, height, constant=False):
    """A valid 8-bit grey PNG of a ramp, or of one value (a few kilobytes at any size)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    row = bytes(90 if constant else x % 256 for x in range(width))
    raw = b"".join(b"\x00" + row for _ in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return (PNG_SIGNATURE + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) +
            chunk(b"IEND", b""))


class Studio:
    def __init__(self, tmp, log, host=None):
        self.tmp = tmp
        self.log = log
        env = dict(os.environ, TMPDIR=str(tmp))
        if "ASAN_OPTIONS" in env:
            # Under AddressSanitizer (scripts/sanitize.sh) freed memory waits in a quarantine of
            # 256 MiB before reuse, which test_memory_stays_bounded would measure as growth; 8 MiB
            # still catches a use soon after free.
            env["ASAN_OPTIONS"] += ":quarantine_size_mb=8"
        arguments = [STOCHTEX, "studio", "--port", "0"] + (["--host", host] if host else [])
        with open(log, "w") as stderr:
            self.process = subprocess.Popen(arguments, env=env, stdout=subprocess.PIPE,
                                            stderr=stderr, text=True)
        line = self.process.stdout.readline()
        prefix = f"stochtex studio: serving http://{host or '127.0.0.1'}:"
        assert line.startswith(prefix), (line, self.stderr())
        # http://HOST:PORT/, with ?token=TOKEN when the studio listens beyond loopback.
        self.url = urllib.parse.urlsplit(line.split()[-1])
        self.port = self.url.port
        self.token = urllib.parse.parse_qs(self.url.query).get("token", [None])[0]

    def request(self, method, path, body=None, headers=None, client="a000000000000001"):
        headers = dict(headers or {})
        if client is not None:
            headers.setdefault("X-Stochtex-Client", client)
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        try:
            connection.request(method, path, body=body, headers=headers)
            response = connection.getresponse()
            return response.status, response.headers, response.read()
        finally:
            connection.close()

    def json(self, method, path, body=None, expect=200, **kwargs):
        if isinstance(body, dict):
            body = json.dumps(body)
        status, headers, data = self.request(method, path, body, **kwargs)
        assert status == expect, (method, path, status, data[:300])
        assert headers["Content-Type"] == "application/json", headers
        return json.loads(data)

    def error(self, method, path, body=None, expect=400, **kwargs):
        """A refused request: the status, a JSON {"error": sentence}, and the server still up."""
        doc = self.json(method, path, body, expect=expect, **kwargs)
        assert list(doc) == ["error"] and len(doc["error"]) > 10, doc
        self.assert_serving()
        return doc["error"]

    def raw(self, data):
        """Sends `data`, a request as bytes, on a connection of its own and returns the status and
        the body of the answer (send `Connection: close`)."""
        answer = b""
        with socket.create_connection(("127.0.0.1", self.port), timeout=30) as connection:
            connection.sendall(data)
            try:
                while chunk := connection.recv(65536):
                    answer += chunk
            except ConnectionResetError:
                pass  # the server stopped reading the request: the answer came first
        head, _, body = answer.partition(b"\r\n\r\n")
        assert head.startswith(b"HTTP/1.1 "), answer[:300]
        return int(head.split()[1]), body

    def stderr(self):
        return self.log.read_text()

    def assert_serving(self):
        assert self.process.poll() is None, self.stderr()
        query = f"?token={self.token}" if self.token else ""
        status, _, _ = self.request("GET", "/api/methods" + query)
        assert status == 200

    def upload(self, data, client="a000000000000001", expect=201, headers=None):
        headers = {"Content-Type": "application/octet-stream", **(headers or {})}
        return self.json("POST", "/api/exemplars", data, expect=expect, headers=headers,
                         client=client)

    def chunked_upload_refused(self, mebibytes):
        """Sends a chunked upload of zeros, which has no Content-Length for the server to check
        first; the server must stop reading it at its limit (the send then fails well before
        the end) and answer 413."""
        with socket.create_connection(("127.0.0.1", self.port), timeout=60) as connection:
            connection.sendall(b"POST /api/exemplars HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n"
                               b"X-Stochtex-Client: a000000000000001\r\n"
                               b"Transfer-Encoding: chunked\r\n\r\n" % self.port)
            chunk = b"%x\r\n" % (1 << 20) + bytes(1 << 20) + b"\r\n"
            sent = 0
            try:
                for sent in range(mebibytes):
                    connection.sendall(chunk)
            except OSError:
                pass
            assert sent < mebibytes - 1, "the server read the whole chunked body"
            response = connection.recv(4096).decode()
        assert response.startswith("HTTP/1.1 413"), response
        self.assert_serving()
        return response

    def analyse(self, exemplar, method, params=None, client="a000000000000001", expect=202,
                colour_space=None):
        body = {"exemplar": exemplar, "method": method, "params": params or {}}
        if colour_space is not None:
            body["colour_space"] = colour_space
        return self.json("POST", "/api/analyses", body, expect=expect, client=client)

    def wait(self, analysis, states, seconds):
        deadline = time.monotonic() + seconds
        while True:
            status = self.json("GET", f"/api/analyses/{analysis}")
            if status["state"] in states or time.monotonic() > deadline:
                return status
            time.sleep(0.05)

    def rss_kib(self):
        with open(f"/proc/{self.process.pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
        raise AssertionError("no VmRSS")


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("studio_tmp")
    server = Studio(tmp, tmp_path_factory.mktemp("studio_log") / "stderr.txt")
    yield server
    if server.process.poll() is None:
        server.process.kill()
        server.process.wait()
    # What the server wrote to stderr (a sanitizer's report among it), shown if a test failed.
    print(server.stderr())


@pytest.fixture(scope="module")
def grass(studio):
    return studio.upload(exemplar_bytes("grass_lawn_128.png"))


def test_page_sets_the_client_cookie(studio):
    status, headers, body = studio.request("GET", "/", client=None)
    assert status == 200 and headers["Content-Type"].startswith("text/html")
    assert b'id="viewer-mount"' in body
    assert headers["Set-Cookie"].startswith("stochtex_client=")
    assert "SameSite=Strict" in headers["Set-Cookie"]
    for name, kind in [("studio/studio.js", "text/javascript"), ("studio/studio.css", "text/css")]:
        status, headers, _ = studio.request("GET", "/web/" + name)
        assert status == 200 and headers["Content-Type"].startswith(kind)


def test_methods_are_the_registry(studio):
    listed = subprocess.run([STOCHTEX, "methods", "--json"], check=True, capture_output=True)
    assert studio.json("GET", "/api/methods") == json.loads(listed.stdout)


def test_languages_are_the_table(studio):
    listed = subprocess.run([STOCHTEX, "languages", "--json"], check=True, capture_output=True)
    assert studio.json("GET", "/api/languages") == json.loads(listed.stdout)


def test_upload_analyse_download(studio, grass, tmp_path):
    assert grass["width"] == 128 and grass["height"] == 128 and grass["channels"] == 3
    # Read as `analyze --colour-space auto` reads the file: its models render linear light.
    assert grass["colour_space"] == "srgb" and "sRGB" in grass["colour"], grass
    for picture in ["image", "gaussian"]:
        status, headers, data = studio.request("GET", f"/api/exemplars/{grass['id']}/{picture}.png")
        assert status == 200 and headers["Content-Type"] == "image/png"
        assert png_size(data) == (128, 128)

    analysis = studio.analyse(grass["id"], "texton", {"order": "cubic", "iterations": 5})
    status = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 60)
    assert status["state"] == "done", status
    assert status["progress"] == 1.0 and status["seconds"] > 0

    model = status["model"]
    code, _, data = studio.request("GET", f"/api/models/{model}.stx")
    assert code == 200
    (tmp_path / "model.stx").write_bytes(data)
    info = subprocess.run([STOCHTEX, "info", str(tmp_path / "model.stx")], capture_output=True,
                          text=True)
    assert info.returncode == 0, info.stderr
    assert "texton" in info.stdout and "order = cubic" in info.stdout
    assert "colour    srgb" in info.stdout
    # Values that are not colour (a height map) are analysed as data when asked.
    analysis = studio.analyse(grass["id"], "texton", {"iterations": 2}, colour_space="data")
    data_model = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 60)["model"]
    (tmp_path / "data.stx").write_bytes(studio.request("GET", f"/api/models/{data_model}.stx")[2])
    info = subprocess.run([STOCHTEX, "info", str(tmp_path / "data.stx")], capture_output=True,
                          text=True)
    assert "colour    data" in info.stdout, info.stdout

    code, _, data = studio.request(
        "GET", f"/api/models/{model}/render.png?width=96&height=40&seed=3&scale=0.5&x=-7&y=2.5")
    assert code == 200 and png_size(data) == (96, 40)
    # The CLI's render of the downloaded model, byte for byte: linear light encoded into a PNG
    # with an sRGB chunk, zoomed out the mean of the decoded colour.
    code, _, zoomed = studio.request(
        "GET", f"/api/models/{model}/render.png?width=32&height=24&seed=3&scale=16&x=5&y=-3")
    assert code == 200 and b"sRGB" in zoomed
    subprocess.run([STOCHTEX, "render", str(tmp_path / "model.stx"), "--size", "32x24", "--seed",
                    "3", "--scale", "16", "--origin", "5,-3", "-o", str(tmp_path / "cli.png")],
                   check=True, capture_output=True)
    assert zoomed == (tmp_path / "cli.png").read_bytes()
    compare = studio.json("GET", f"/api/models/{model}/compare?seed=2")
    assert compare["model"] == model and compare["seed"] == 2
    for key in ["spectral_error", "spectral_error_adsn", "histogram_error", "covariance_error"]:
        assert 0 <= compare[key] < 10, (key, compare)


def test_auto_says_its_choice_as_the_cli_does(studio, grass, tmp_path):
    # "auto" is chosen by the server from the upload, as `analyze -m auto` chooses from the file.
    analysis = studio.analyse(grass["id"], "auto", client="a000000000000003")
    assert analysis["method"] == "texton" and analysis["chosen_by"] == "auto", analysis
    assert analysis["reason"].startswith("texton: close to Gaussian ("), analysis
    status = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 60)
    assert status["state"] == "done" and status["reason"] == analysis["reason"], status
    cli = subprocess.run([STOCHTEX, "analyze", os.path.join(EXEMPLARS, "grass_lawn_128.png"), "-m",
                          "auto", "-o", str(tmp_path / "auto.stx")], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert "--method auto chose " + analysis["reason"] in cli.stderr, cli.stderr
    assert "auto" in studio.error("POST", "/api/analyses", {
        "exemplar": grass["id"], "method": "auto", "params": {"iterations": 2}})


def test_shader_export_downloads(studio, grass, tmp_path):
    # The zip of /shader-<variant>-<language>.zip holds export-shader's files, byte for byte.
    analysis = studio.analyse(grass["id"], "texton", {"iterations": 5})
    status = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 60)
    assert status["state"] == "done", status
    model = status["model"]
    _, _, stx = studio.request("GET", f"/api/models/{model}.stx")
    (tmp_path / "model.stx").write_bytes(stx)
    for variant, language in [("exact", "glsl"), ("fast", "essl")]:
        code, headers, data = studio.request(
            "GET", f"/api/models/{model}/shader-{variant}-{language}.zip")
        assert code == 200 and headers["Content-Type"] == "application/zip"
        folder = tmp_path / f"{variant}-{language}"
        subprocess.run([STOCHTEX, "export-shader", str(tmp_path / "model.stx"), "-o", str(folder),
                        "--variant", variant, "--language", language], check=True,
                       capture_output=True)
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            files = {name: archive.read(name) for name in archive.namelist()}
        assert sorted(files) == sorted(path.name for path in folder.iterdir())
        assert "README.md" in files
        for name, content in files.items():
            assert content == (folder / name).read_bytes(), name
    # Any word reaches the export, which names the languages it writes.
    code, _, body = studio.request("GET", f"/api/models/{model}/shader-exact-cuda.zip")
    assert code == 404
    message = json.loads(body)["error"]
    assert "'cuda'" in message, message
    for language in studio.json("GET", "/api/languages"):
        assert language["name"] in message, message


def test_bad_uploads_are_refused(studio):
    assert "not a PNG, OpenEXR, PFM, JPEG, TIFF, WebP or TGA" in studio.error(
        "POST", "/api/exemplars", b"hello, not an image",
        headers={"Content-Type": "application/octet-stream"})
    truncated = exemplar_bytes("grass_lawn_128.png")[:2000]
    assert "truncated" in studio.error("POST", "/api/exemplars", truncated,
                                       headers={"Content-Type": "application/octet-stream"})
    assert "limit of 16777216 bytes" in studio.error(
        "POST", "/api/exemplars", b"\0" * (16 * 1024 * 1024 + 1), expect=413,
        headers={"Content-Type": "application/octet-stream"})
    assert "limit of 16777216 bytes" in studio.chunked_upload_refused(128)
    assert "limit of 24000000 pixels" in studio.error(
        "POST", "/api/exemplars", grey_png(6001, 4000),
        headers={"Content-Type": "application/octet-stream"})
    assert "constant" in studio.error("POST", "/api/exemplars", grey_png(16, 16, constant=True),
                                      headers={"Content-Type": "application/octet-stream"})
    assert "client id" in studio.error("POST", "/api/exemplars", grey_png(16, 16), expect=403,
                                       client=None)


def test_large_photos_are_downscaled(studio):
    """A photo longer than 1024 pixels is kept downscaled (in linear light), and the answer says so."""
    info = studio.json("POST", "/api/exemplars", grey_png(2048, 1536), expect=201,
                       headers={"Content-Type": "application/octet-stream"})
    assert (info["width"], info["height"]) == (1024, 768), info
    assert "downscaled to 1024x768 (a factor of 0.5); crop the photo first" in info["note"], info
    small = studio.json("POST", "/api/exemplars", grey_png(64, 64), expect=201,
                        headers={"Content-Type": "application/octet-stream"})
    assert small["note"] == "", small


def test_bad_analyses_and_queries_are_refused(studio, grass):
    exemplar = grass["id"]
    bad_params = [
        ({"iterations": "nan"}, "iterations"),
        ({"iterations": "inf"}, "iterations"),
        ({"iterations": 1e300}, "iterations"),
        ({"order": "sextic"}, "order"),
        ({"bogus": 1}, "unknown parameter 'bogus'"),
        ({"iterations": [1]}, "number or a choice"),
    ]
    for params, words in bad_params:
        assert words in studio.error("POST", "/api/analyses", {
            "exemplar": exemplar, "method": "texton", "params": params}), params
    for colour_space in ["srgb-ish", 3]:
        assert "colour_space" in studio.error("POST", "/api/analyses", {
            "exemplar": exemplar, "method": "texton", "colour_space": colour_space}), colour_space
    assert "unknown method" in studio.error("POST", "/api/analyses",
                                            {"exemplar": exemplar, "method": "nope"})
    # NaN is not JSON: Python writes it as a bare NaN, which the server must refuse.
    assert "not a JSON object" in studio.error(
        "POST", "/api/analyses",
        json.dumps({"exemplar": exemplar, "method": "texton", "params": {"mni": float("nan")}}))
    assert "seed" in studio.error("POST", "/api/analyses",
                                  {"exemplar": exemplar, "method": "texton", "seed": -1})
    assert "no exemplar" in studio.error("POST", "/api/analyses",
                                         {"exemplar": "0" * 16, "method": "texton"}, expect=404)
    assert "no analysis" in studio.error("GET", "/api/analyses/" + "0" * 16, expect=404)
    assert "no model" in studio.error("GET", f"/api/models/{'0' * 16}.stx", expect=404)

    analysis = studio.analyse(exemplar, "texton", {"iterations": 2}, client="a000000000000002")
    model = studio.wait(analysis["id"], {"done"}, 60)["model"]
    for query in ["width=0", "width=2049", "height=-3", "width=1.5", "width=nan", "scale=nan",
                  "scale=inf", "x=1e300", "seed=-1", "seed=4294967296", "y=abc"]:
        studio.error("GET", f"/api/models/{model}/render.png?{query}")
    studio.error("GET", f"/api/models/{model}/compare?seed=x")


TRAVERSALS = [
    "/web/../CMakeLists.txt",
    "/web/%2e%2e/CMakeLists.txt",
    "/web/%2E%2E%2FCMakeLists.txt",
    "/web/..%2f..%2fCMakeLists.txt",
    "/web/studio/..%2f..%2f..%2fCMakeLists.txt",
    "/web/%2e%2e%2f%2e%2e%2f%2e%2e%2f%2e%2e%2fetc%2fpasswd",
    "//etc/passwd",
    "/web//etc/passwd",
    "/web/%2fetc%2fpasswd",
    "/..%2f..%2fetc%2fpasswd",
    "/api/models/../../etc/passwd",
    "/web/studio/index.html%00.png",
    "/web/studio/",
    "/CMakeLists.txt",
    "/web/studio/index.html/..",
]


def test_path_traversal_finds_nothing(studio):
    for path in TRAVERSALS:
        status, headers, body = studio.request("GET", path)
        assert status == 404, (path, status)
        assert headers["Content-Type"] == "application/json", path
        assert b"cmake_minimum_required" not in body and b"root:" not in body, path
        assert "error" in json.loads(body), path
    studio.assert_serving()


def test_other_host_names_are_refused(studio):
    # A page elsewhere pointing its own name at 127.0.0.1 (DNS rebinding) gets nothing.
    status, _, body = studio.request("GET", "/api/methods", headers={"Host": "evil.example"})
    assert status == 403 and "localhost" in json.loads(body)["error"]
    status, _, _ = studio.request("GET", "/api/methods", headers={"Host": f"localhost:{studio.port}"})
    assert status == 200


def test_twenty_concurrent_requests(studio, grass):
    paths = ["/", "/api/methods", "/web/studio/studio.js",
             f"/api/exemplars/{grass['id']}/image.png", f"/api/exemplars/{grass['id']}/gaussian.png"]
    barrier = threading.Barrier(20)
    results = [None] * 20

    def fetch(index):
        barrier.wait()
        status, _, body = studio.request("GET", paths[index % len(paths)])
        results[index] = (status, len(body))

    threads = [threading.Thread(target=fetch, args=(i,)) for i in range(20)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(60)
    assert all(result is not None and result[0] == 200 and result[1] > 0 for result in results), \
        results


def test_cancel_one_analysis_at_a_time_and_a_bounded_queue(studio):
    # gabor on a 256 exemplar takes about 10 s: long enough to be cancelled while it runs.
    slow = studio.upload(exemplar_bytes("wood_planks_256.png"), client="b000000000000001")
    running = studio.analyse(slow["id"], "gabor", client="b000000000000001")
    status = studio.wait(running["id"], {"running"}, 30)
    assert status["state"] == "running", status

    # The same client's second analysis is refused; other clients queue, up to the limit of 4.
    assert "already has an analysis" in studio.error(
        "POST", "/api/analyses", {"exemplar": slow["id"], "method": "texton"}, expect=429,
        client="b000000000000001")
    queued = [studio.analyse(slow["id"], "texton", client=f"c00000000000000{i}")
              for i in range(4)]
    assert all(analysis["state"] == "queued" for analysis in queued)
    assert "queue is full" in studio.error(
        "POST", "/api/analyses", {"exemplar": slow["id"], "method": "texton"}, expect=503,
        client="c000000000000009")
    assert "another browser" in studio.error("DELETE", f"/api/analyses/{running['id']}",
                                             expect=403, client="c000000000000000")
    for i, analysis in enumerate(queued):
        cancelled = studio.json("DELETE", f"/api/analyses/{analysis['id']}",
                                client=f"c00000000000000{i}")
        assert cancelled["state"] == "cancelled", cancelled

    time.sleep(0.5)  # into the analysis' iterations
    started = time.monotonic()
    studio.json("DELETE", f"/api/analyses/{running['id']}", client="b000000000000001")
    status = studio.wait(running["id"], {"cancelled", "done", "failed"}, 10)
    stopped = time.monotonic() - started
    assert status["state"] == "cancelled" and stopped < 3, (status, stopped)
    studio.assert_serving()

    # The client may start again, and the worker runs the next analysis.
    again = studio.analyse(slow["id"], "texton", {"iterations": 2}, client="b000000000000001")
    assert studio.wait(again["id"], {"done", "failed", "cancelled"}, 60)["state"] == "done"


@pytest.fixture(scope="module")
def plaid_gabor(studio):
    """A gabor model of the plaid (light parameters: about 4 s) and its groups: 71 periodic
    Gaussians of 25k holding 64% of the variance. As data: each edit of a srgb model measures
    its removed deviations again, seconds under the sanitizers."""
    plaid = studio.upload(exemplar_bytes("plaid_fabric_256.png"))
    analysis = studio.analyse(plaid["id"], "gabor", {"iterations": 50, "impulses": 64},
                              colour_space="data")
    status = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 120)
    assert status["state"] == "done", status
    return status["model"]


def test_gabor_groups_are_the_clis(studio, plaid_gabor, tmp_path):
    groups = studio.json("GET", f"/api/models/{plaid_gabor}/groups")
    assert list(groups["groups"]) == ["periodic", "anisotropic", "stochastic"]
    counts = [group["gaussians"] for group in groups["groups"].values()]
    assert sum(counts) == groups["gaussians"] and groups["groups"]["periodic"]["gaussians"] > 0
    assert sum(group["variance_share"] for group in groups["groups"].values()) == \
        pytest.approx(1.0, abs=1e-9)
    _, _, data = studio.request("GET", f"/api/models/{plaid_gabor}.stx")
    (tmp_path / "plaid.stx").write_bytes(data)
    listed = subprocess.run([STOCHTEX, "edit", str(tmp_path / "plaid.stx"), "--list-groups",
                             "--json"], check=True, capture_output=True)
    assert groups == json.loads(listed.stdout)


def test_an_edit_of_the_periodic_group(studio, plaid_gabor, tmp_path):
    edit = {"group": "periodic", "rotate": 30, "magnitude": 1.5}
    edited = studio.json("POST", f"/api/models/{plaid_gabor}/edit", edit, expect=201)["model"]
    assert edited != plaid_gabor
    query = "render.png?width=64&height=64&seed=1"
    renders = [studio.request("GET", f"/api/models/{model}/{query}") for model in
               [plaid_gabor, edited]]
    assert all(code == 200 for code, _, _ in renders) and renders[0][2] != renders[1][2]
    # The edited model is the CLI's edit of the same model, byte for byte.
    for name, model in [("plaid.stx", plaid_gabor), ("studio.stx", edited)]:
        _, _, data = studio.request("GET", f"/api/models/{model}.stx")
        (tmp_path / name).write_bytes(data)
    subprocess.run([STOCHTEX, "edit", str(tmp_path / "plaid.stx"), "-o", str(tmp_path / "cli.stx"),
                    "--group", "periodic", "--rotate", "30", "--magnitude", "1.5"], check=True,
                   capture_output=True)
    assert (tmp_path / "studio.stx").read_bytes() == (tmp_path / "cli.stx").read_bytes()
    info = subprocess.run([STOCHTEX, "info", str(tmp_path / "studio.stx")], capture_output=True,
                          text=True)
    assert info.returncode == 0 and "gabor" in info.stdout, info.stderr
    for route in ["web/exact/manifest.json", "compare"]:
        assert studio.request("GET", f"/api/models/{edited}/{route}")[0] == 200


def test_bad_edits_are_refused(studio, plaid_gabor, grass):
    path = f"/api/models/{plaid_gabor}/edit"
    assert "no Gaussian" in studio.error("POST", path, {"magnitude": 0})
    for body, words in [({"rotate": "NaN"}, "rotate"), ({"scale": -1}, "scale"),
                        ({"magnitude": 1e9}, "magnitude"), ({"bandwidth": 3}, "power of two"),
                        ({"translate": [2, 0]}, "translate"), ({"translate": 0.1}, "translate"),
                        ({"group": "nosuch"}, "nosuch"), ({"spin": 1}, "spin"),
                        ("not json", "JSON object")]:
        assert words in studio.error("POST", path, body), body
    assert "client id" in studio.error("POST", path, {}, expect=403, client=None)
    texton = studio.analyse(grass["id"], "texton", {"iterations": 2})
    status = studio.wait(texton["id"], {"done", "failed", "cancelled"}, 60)
    for method, route in [("GET", "groups"), ("POST", "edit")]:
        assert "texton model" in studio.error(method, f"/api/models/{status['model']}/{route}", {})
        studio.error(method, f"/api/models/0123456789abcdef/{route}", {}, expect=404)


def test_edits_replace_only_edits(studio, plaid_gabor):
    # The page edits the original model each time: the studio keeps the last 4 edited models,
    # evicting older edits and never the analysed models.
    path = f"/api/models/{plaid_gabor}/edit"
    edits = [studio.json("POST", path, {"scale": 1 + k / 10}, expect=201)["model"]
             for k in range(6)]
    assert studio.request("GET", f"/api/models/{edits[0]}/groups")[0] == 404
    assert studio.request("GET", f"/api/models/{edits[-1]}/groups")[0] == 200
    assert studio.request("GET", f"/api/models/{plaid_gabor}/groups")[0] == 200


def test_memory_stays_bounded(studio):
    # The studio keeps the last 8 exemplars: after 10 uploads of a 256x256 exemplar (each with
    # its Gaussian version) the store is full; 30 more must not grow the server by more than
    # 16 MiB. Measured over 4 runs: +0.4 MiB; with the eviction off (8 raised to 1000) +29.9 MiB,
    # the 1 MiB each upload keeps (0.75 MiB of float pixels and two PNGs). (A 512x512 exemplar
    # gave -0.5 to +0.7 and +136 MiB, in 15 s instead of 3.6 s.)
    data = exemplar_bytes("wood_planks_256.png")

    def upload_some(count):
        for _ in range(count):
            exemplar = studio.upload(data, client="d000000000000001")
            status, _, _ = studio.request("GET", f"/api/exemplars/{exemplar['id']}/gaussian.png")
            assert status == 200

    upload_some(10)
    before = studio.rss_kib()
    upload_some(30)
    after = studio.rss_kib()
    print(f"studio RSS {before} KiB -> {after} KiB after 30 uploads")
    # Under AddressSanitizer (scripts/sanitize.sh) the resident size is its allocator's, which
    # keeps the pages of freed chunks: the same 30 uploads measured +28 to +29 MiB on a server
    # that had just started (a build of main before this check was written too) and +17 MiB after
    # the other tests, whatever the store keeps. There LeakSanitizer checks that nothing is lost;
    # the release tier measures the growth.
    if "ASAN_OPTIONS" not in os.environ:
        assert after - before < 16 * 1024, (before, after)
    studio.assert_serving()


# The tests below upload and analyse freely: they come after the ones that use the module's
# exemplars and models, which the store may evict.


def test_host_must_name_this_studio(studio):
    # A loopback studio answers only requests to its loopback names with its port (DNS rebinding
    # points other names at 127.0.0.1), in exactly one Host header. These all passed when any name
    # starting with "127." did, or any port.
    port = studio.port
    for host in ["127.evil.example", f"127.0.0.1.nip.io:{port}", f"127.0.0.1@evil.example:{port}",
                 f"localhost:{port}.evil.example", f"127.0.0.2:{port}", f"127.0.0.1:{port + 1}",
                 "127.0.0.1", "evil.example"]:
        error = studio.error("GET", "/api/methods", expect=403, headers={"Host": host})
        assert f"localhost:{port}, 127.0.0.1:{port}" in error, (host, error)
    for host in [f"localhost:{port}", f"127.0.0.1:{port}", f"[::1]:{port}", f"LocalHost:{port}"]:
        assert studio.request("GET", "/api/methods", headers={"Host": host})[0] == 200, host
    line = b"GET /api/methods HTTP/1.1\r\n"
    for hosts in [b"", b"Host: 127.0.0.1:%d\r\nHost: evil.example\r\n" % port]:
        status, body = studio.raw(line + hosts + b"Connection: close\r\n\r\n")
        assert status == 400 and "exactly one Host header" in json.loads(body)["error"], \
            (hosts, status, body[:300])
    studio.assert_serving()


def test_changes_from_other_origins_are_refused(studio):
    # A page elsewhere, another localhost port among them (same-site: its requests carry the
    # cookie), cannot change anything: browsers send Origin with every POST and DELETE, and
    # Sec-Fetch-Site with every request. These uploads were all taken.
    port = studio.port
    own = f"http://127.0.0.1:{port}"
    png = grey_png(16, 16)
    for headers in [{"Origin": "http://evil.example"}, {"Origin": f"http://localhost:{port + 1}"},
                    {"Origin": f"http://localhost:{port}"}, {"Origin": f"https://127.0.0.1:{port}"},
                    {"Origin": "null"}, {"Sec-Fetch-Site": "cross-site"},
                    {"Sec-Fetch-Site": "same-site"}, {"Origin": own, "Sec-Fetch-Site": "same-site"}]:
        error = studio.error("POST", "/api/exemplars", png, expect=403,
                             headers={"Content-Type": "application/octet-stream", **headers})
        assert "its own page" in error, (headers, error)
    other = {"Origin": "http://evil.example"}
    unknown = "0" * 16
    studio.error("POST", "/api/analyses", {"exemplar": unknown, "method": "texton"}, expect=403,
                 headers=other)
    studio.error("DELETE", f"/api/analyses/{unknown}", expect=403, headers=other)
    studio.error("POST", f"/api/models/{unknown}/edit", {}, expect=403, headers=other)
    # The studio's own page, and scripts (neither header).
    for headers in [{"Origin": own}, {"Origin": own, "Sec-Fetch-Site": "same-origin"},
                    {"Sec-Fetch-Site": "none"}, {}]:
        studio.upload(png, headers=headers)
    # Reads change nothing and stay open: a page elsewhere knows no id to read.
    status, _, _ = studio.request("GET", "/api/methods",
                                  headers={**other, "Sec-Fetch-Site": "cross-site"})
    assert status == 200


def test_slow_and_idle_clients_do_not_stop_it(studio):
    # 16 idle connections, 16 clients sending their headers a byte at a time and 8 uploads that
    # stall after their headers: they held all 8 request threads, and the API stopped answering.
    # Now each connection has a thread of its own (up to 64), an idle one is closed after 2 s and a
    # request's head must arrive within 3 s of its first byte, however slowly it trickles.
    port = studio.port

    def connect(data=b""):
        connection = socket.create_connection(("127.0.0.1", port), timeout=10)
        connection.sendall(data)
        return connection

    opened = time.monotonic()
    idle = [connect() for _ in range(16)]
    slow = [connect(b"GET /api/methods HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nX-Slow: " % port)
            for _ in range(16)]
    uploads = [connect(b"POST /api/exemplars HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n"
                       b"X-Stochtex-Client: a000000000000001\r\nContent-Length: 100000\r\n\r\n"
                       b"\x89PNG" % port) for _ in range(8)]
    time.sleep(0.3)
    started = time.monotonic()
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=1.5)
    try:
        connection.request("GET", "/api/methods")
        status = connection.getresponse().status
    except TimeoutError:
        status = None
    finally:
        connection.close()
    answered = time.monotonic() - started
    assert status == 200 and answered < 1.0, (status, answered)

    # The server closes the idle connections and the slow heads, which keep trickling.
    closed = {}
    while len(closed) < len(idle) + len(slow) and time.monotonic() < opened + 8:
        open_ones = [c for c in idle + slow if c not in closed]
        readable, _, _ = select.select(open_ones, [], [], 0.1)
        for connection in readable:
            closed[connection] = time.monotonic() - opened
        for connection in open_ones:
            if connection in slow and connection not in closed:
                try:
                    connection.send(b"a")
                except OSError:
                    closed[connection] = time.monotonic() - opened
    for connection in idle + slow + uploads:
        connection.close()
    assert all(closed.get(c, 99) < 4 for c in idle), sorted(closed.get(c) for c in idle)
    assert all(closed.get(c, 99) < 5 for c in slow), sorted(closed.get(c) for c in slow)
    studio.assert_serving()


def test_a_request_head_is_bounded(studio):
    # 70 headers of 1 kB: httplib keeps any number of them; the studio reads up to 64 KiB.
    filler = b"".join(b"X-Filler-%d: %s\r\n" % (i, b"a" * 1000) for i in range(70))
    status, body = studio.raw(b"GET /api/methods HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n%s"
                              b"Connection: close\r\n\r\n" % (studio.port, filler))
    assert status == 400 and "64 KiB" in json.loads(body)["error"], (status, body[:300])
    studio.assert_serving()


def test_a_network_studio_needs_its_token(studio, tmp_path):
    # Beyond loopback (--host 0.0.0.0) any name may reach the studio, so the Host check cannot
    # hold: every request needs the token printed with the address, as Jupyter's, which the page's
    # address sets as a cookie of this port's. A loopback studio prints none.
    assert studio.token is None and studio.url.path == "/", studio.url
    network = Studio(tmp_path, tmp_path / "stderr.txt", host="0.0.0.0")
    try:
        token = network.token
        assert token is not None and len(token) == 32, network.url
        assert "not loopback" in network.stderr() and "token" in network.stderr()
        png = grey_png(16, 16)
        octet = {"Content-Type": "application/octet-stream"}
        for path in ["/", "/web/studio/studio.js", "/api/methods", f"/api/methods?token={'0' * 32}"]:
            assert "token" in network.error("GET", path, expect=403), path
        assert "token" in network.error("POST", "/api/exemplars", png, expect=403, headers=octet)

        status, headers, _ = network.request("GET", f"/?token={token}", client=None)
        assert status == 200
        cookie = f"stochtex_token_{network.port}={token}"
        assert any(value.startswith(cookie + ";") and "HttpOnly" in value and
                   "SameSite=Strict" in value for value in headers.get_all("Set-Cookie")), headers
        with_cookie = {"Cookie": cookie}
        assert network.request("GET", "/api/methods", headers=with_cookie)[0] == 200
        assert network.request("GET", f"/api/methods?token={token}")[0] == 200
        other_name = {**with_cookie, "Host": f"studio.example:{network.port}"}
        assert network.request("GET", "/api/methods", headers=other_name)[0] == 200
        assert "its own page" in network.error(
            "POST", "/api/exemplars", png, expect=403,
            headers={**octet, **with_cookie, "Origin": "http://evil.example"})
        network.upload(png, headers=with_cookie)
    finally:
        network.process.send_signal(signal.SIGINT)
        assert network.process.wait(10) == 0


def test_render_scales_are_the_clis(studio, tmp_path):
    # render.png took scale 0, -1 and 1e-300, which `stochtex render --scale` refuses.
    exemplar = studio.upload(exemplar_bytes("grass_lawn_128.png"))
    analysis = studio.analyse(exemplar["id"], "texton", {"iterations": 2})
    model = studio.wait(analysis["id"], {"done", "failed", "cancelled"}, 60)["model"]
    (tmp_path / "model.stx").write_bytes(studio.request("GET", f"/api/models/{model}.stx")[2])

    def cli(scale):
        return subprocess.run([STOCHTEX, "render", str(tmp_path / "model.stx"), "-o",
                               str(tmp_path / "render.png"), "--size", "8x8", f"--scale={scale}"],
                              capture_output=True, text=True)

    path = f"/api/models/{model}/render.png?width=8&height=8&scale="
    for scale in ["0", "-1", "1e-300", "9e-7", "1.1e6"]:
        assert "scale" in studio.error("GET", path + scale), scale
        assert cli(scale).returncode == 2, scale
    for scale in ["1e-6", "4"]:
        assert studio.request("GET", path + scale)[0] == 200, scale
        assert cli(scale).returncode == 0, scale


def test_only_methods_of_one_exemplar_are_analysed(studio):
    # texton_mix is made from two exemplars (`stochtex mix`): its analysis was queued, then failed.
    exemplar = studio.upload(grey_png(16, 16))
    error = studio.error("POST", "/api/analyses", {"exemplar": exemplar["id"],
                                                   "method": "texton_mix"})
    assert "texton_mix" in error, error
    for method in studio.json("GET", "/api/methods"):
        assert method["name"] in error, error


def test_ids_tell_nothing_of_other_ids(studio):
    # The ids were splitmix64 of a counter, which inverts: one id gave the others, and with them
    # every exemplar and model of the studio.
    gamma, mask = 0x9E3779B97F4A7C15, (1 << 64) - 1

    def unmix(z):
        for shift, factor in [(31, 0x94D049BB133111EB), (27, 0xBF58476D1CE4E5B9), (30, None)]:
            y = z
            for _ in range(64 // shift + 1):
                y = z ^ (y >> shift)
            z = y if factor is None else y * pow(factor, -1, 1 << 64) & mask
        return z

    first, second = (int(studio.upload(grey_png(16, 16))["id"], 16) for _ in range(2))
    step = (unmix(second) - unmix(first)) & mask
    assert all(step != k * gamma & mask for k in range(1, 1000)), hex(step)


def test_a_second_server_cannot_take_the_port(studio):
    second = subprocess.run([STOCHTEX, "studio", "--port", str(studio.port)], capture_output=True,
                            text=True, timeout=30)
    assert second.returncode == 1 and "cannot listen on 127.0.0.1 port" in second.stderr, second
    studio.assert_serving()


def test_sigint_stops_it_cleanly(studio):
    # Every test before this one has uploaded, rendered and exported through the server.
    assert list(studio.tmp.iterdir()) == []
    studio.process.send_signal(2)
    assert studio.process.wait(10) == 0
    assert list(studio.tmp.iterdir()) == []
