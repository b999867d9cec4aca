// The viewer (viewer.hpp, viewer_server.hpp, image_encode.hpp, living_picture.hpp): parsing and
// routing without sockets, then the real server with malformed, oversized and concurrent requests.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "lfcam/edof/depth.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/focus_spread.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "lfcam/viewer/viewer_server.hpp"
#include "test_support.hpp"
#include "viewer/image_encode.hpp"

namespace lfcam {
namespace {

// 5x5 views of 64x64: small enough for every render here to take milliseconds.
LayeredPlanesLightField smallScene() { return renderLayeredPlanes(defaultLayeredPlanesScene(5, 64, 3)); }

ViewerSession& session() {
  static ViewerSession* shared = [] {
    auto scene = smallScene();
    return new ViewerSession(std::move(scene.lightField), ViewerLimits{.cacheBytes = 200000});
  }();
  return *shared;
}

ViewerAnswer get(const std::string& path, std::multimap<std::string, std::string> params = {}) {
  return answerRequest(session(), {"GET", path, std::move(params)});
}

bool isJpeg(const std::string& bytes) {
  return bytes.size() > 4 && std::uint8_t(bytes[0]) == 0xFF && std::uint8_t(bytes[1]) == 0xD8;
}

TEST(ImageEncode, JpegAndPngDecodeBackToTheImage) {
  Image image(17, 9, 3);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 17; ++x) image.at(x, y, c) = float(x + y + c) / 30.0f;
  test::TempDir dir;
  for (auto format : {EncodedFormat::Png, EncodedFormat::Jpeg}) {
    auto bytes = encodeImage(image, {.format = format, .jpegQuality = 95});
    ASSERT_TRUE(bytes.ok());
    const auto path = dir.path() / (format == EncodedFormat::Png ? "a.png" : "a.jpg");
    test::writeBytes(path, *bytes);
    auto back = readImage(path);
    ASSERT_TRUE(back.ok()) << back.error().message;
    ASSERT_EQ(back->width(), 17);
    ASSERT_EQ(back->height(), 9);
    double worst = 0;
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 17; ++x) worst = std::max(worst, std::abs(double(back->at(x, y, c)) - image.at(x, y, c)));
    EXPECT_LT(worst, format == EncodedFormat::Png ? 0.005 : 0.05);
  }
  EXPECT_TRUE(encodeImage(Image(4, 4, 2)).ok());  // grey from the first channel
  EXPECT_TRUE(encodeImage(Image(4, 4, 5)).ok());  // RGB from the first three
  EXPECT_FALSE(encodeImage(Image()).ok());
}

TEST(ImageEncode, Base64MatchesRfc4648) {
  EXPECT_EQ(base64Encode(""), "");
  EXPECT_EQ(base64Encode("f"), "Zg==");
  EXPECT_EQ(base64Encode("fo"), "Zm8=");
  EXPECT_EQ(base64Encode("foo"), "Zm9v");
  EXPECT_EQ(base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64Encode(std::string("\xff\x00\x10", 3)), "/wAQ");
}

TEST(ViewerRoutes, ServesTheEmbeddedPageAndNothingElse) {
  auto page = get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("viewer.js"), std::string::npos);
  EXPECT_EQ(get("/viewer.js").status, 200);
  EXPECT_EQ(get("/viewer.css").contentType.rfind("text/css", 0), 0u);
  EXPECT_EQ(get("/viewer.dual-range.css").contentType.rfind("text/css", 0), 0u);
  // The export template and anything that looks like a path stay out of reach.
  for (const char* path : {"/living.html", "/../etc/passwd", "/viewer.js/../../etc/passwd", "/etc/passwd",
                           "//etc/passwd", "/api/../viewer.js", "/api", "", "/viewer.jsx", "/VIEWER.JS"})
    EXPECT_EQ(get(path).status, 404) << path;
  EXPECT_EQ(answerRequest(session(), {"POST", "/api/image", {}}).status, 405);
  EXPECT_EQ(answerRequest(session(), {"DELETE", "/", {}}).status, 405);
}

TEST(ViewerRoutes, ServePageAnswersItsPageAndNothingElse) {
  const auto answer = servePage("<html>one page</html>");
  for (const char* path : {"/", "/index.html"}) {
    const ViewerAnswer page = answer({"GET", path, {}});
    EXPECT_EQ(page.status, 200) << path;
    EXPECT_EQ(page.body, "<html>one page</html>");
    EXPECT_EQ(page.contentType.rfind("text/html", 0), 0u);
  }
  for (const char* path : {"/viewer.js", "/../etc/passwd", "", "/index.htm"})
    EXPECT_EQ(answer({"GET", path, {}}).status, 404) << path;
  EXPECT_EQ(answer({"POST", "/", {}}).status, 405);
}

TEST(ViewerRoutes, RefusesBadParameters) {
  using P = std::multimap<std::string, std::string>;
  for (const P& params : std::vector<P>{{{"slope", "abc"}},
                                        {{"slope", "nan"}},
                                        {{"slope", "1e300"}},
                                        {{"slope", "1x"}},
                                        {{"slope", ""}},
                                        {{"slope", "1"}, {"slope", "2"}},
                                        {{"f-number", "0.5"}},
                                        {{"q", "101"}},
                                        {{"layer", "secret"}},
                                        {{"focus-at", "3"}},
                                        {{"focus-at", "64,3"}},
                                        {{"focus-at", "-1,3"}},
                                        {{"aperture-mask", "/etc/passwd"}},  // no file is read on a query
                                        {{"path", "/etc/passwd"}}})
    EXPECT_EQ(get("/api/image", params).status, 400) << params.begin()->first << "=" << params.begin()->second;
  EXPECT_EQ(get("/api/focus", {{"x", "3"}}).status, 400);
  EXPECT_EQ(get("/api/focus", {{"x", "300"}, {"y", "3"}}).status, 400);
  EXPECT_EQ(get("/api/info", {{"x", "1"}}).status, 400);
}

// The photograph request's own refusals (tests/photo_request/refusals.json) are held to the same
// lines through the viewer in photo_request_test.cpp; here what the viewer adds.
TEST(ViewerRoutes, RefusesInOneLineAndAcceptsEveryCombination) {
  using P = std::multimap<std::string, std::string>;
  const std::vector<std::pair<P, std::string>> cases = {
      {{{"focus-plane", "10,10:20,20:30,30.5"}}, "lie on one line"},  // within a pixel of the line
      {{{"focus-plane", "5,5:50,10:20,50"}, {"layer", "depth"}}, "take no photo setting"},
      {{{"slope", "100"}}, "slope: expected a number in"},
  };
  for (const auto& [params, words] : cases) {
    const auto answer = get("/api/image", params);
    EXPECT_EQ(answer.status, 400) << params.begin()->first << "=" << params.begin()->second;
    EXPECT_NE(answer.body.find(words), std::string::npos) << answer.body;
    EXPECT_EQ(answer.body.find('\n'), answer.body.size() - 1) << answer.body;  // one line
  }
  // Accepted: the values at their limits, a range of one slope, and the combinations the page
  // could not ask for before (a tilt or a finer grid through a stopped-down aperture).
  for (const P& params : std::vector<P>{{{"upsample", "1"}, {"f-number", "2"}},
                                        {{"upsample", "4"}, {"focus-at", "3,3"}},
                                        {{"focus-range", "0.5:0.5"}},
                                        {{"focus-plane", "5,5:50,10:20,50"}, {"f-number", "2"}},
                                        {{"upsample", "2"}, {"f-number", "2"}, {"aperture-centre", "1,0"}},
                                        {{"focus-range", "1:0"}, {"f-number", "3"}}})
    EXPECT_TRUE(parseViewerView(params, session()).ok()) << params.begin()->first << "=" << params.begin()->second;
}

TEST(ViewerRoutes, ClampsTheObserverToTheLens) {
  auto view = parseViewerView({{"f-number", "2"}, {"aperture-centre", "100,-100"}}, session());
  ASSERT_TRUE(view.ok());
  EXPECT_EQ(view->photo.at("aperture-centre"), "2,-2");
}

TEST(ViewerSession, ClickFocusesThePlaneUnderThePointer) {
  auto scene = smallScene();
  ViewerSession local(std::move(scene.lightField));
  // The nearest and the farthest surfaces of the scene, by the ground truth.
  const Image& truth = scene.disparity;
  // Points whose whole focus window (7x7, and a margin) lies on one surface.
  auto flat = [&](int x, int y) {
    for (int dy = -5; dy <= 5; ++dy)
      for (int dx = -5; dx <= 5; ++dx)
        if (std::abs(truth.at(x + dx, y + dy, 0) - truth.at(x, y, 0)) > 0.01f) return false;
    return true;
  };
  int nearX = -1, nearY = -1, farX = -1, farY = -1;
  for (int y = 8; y < 56; ++y)
    for (int x = 8; x < 56; ++x) {
      if (!flat(x, y)) continue;
      if (nearX < 0 || truth.at(x, y, 0) > truth.at(nearX, nearY, 0)) nearX = x, nearY = y;
      if (farX < 0 || truth.at(x, y, 0) < truth.at(farX, farY, 0)) farX = x, farY = y;
    }
  ASSERT_GE(nearX, 0);
  ASSERT_GT(truth.at(nearX, nearY, 0) - truth.at(farX, farY, 0), 0.5f);
  for (auto [x, y] : {std::pair{nearX, nearY}, std::pair{farX, farY}}) {
    auto answer =
        answerRequest(local, {"GET", "/api/image", {{"focus-at", std::to_string(x) + "," + std::to_string(y)}}});
    ASSERT_EQ(answer.status, 200) << answer.body;
    EXPECT_TRUE(isJpeg(answer.body));
    EXPECT_NEAR(std::stod(answer.headers["X-Lfcam-Slope"]), truth.at(x, y, 0), 0.25) << x << "," << y;
  }
}

TEST(ViewerSession, RendersEveryControlAndKeepsTheCacheBounded) {
  for (int i = 0; i < 40; ++i) {
    auto answer = get("/api/image", {{"slope", std::to_string(-1 + 0.05 * i)},
                                     {"f-number", std::to_string(1 + i % 12)},
                                     {"aperture-centre", std::to_string((i % 5) - 2.0) + ",0.5"},
                                     {"q", "90"}});
    ASSERT_EQ(answer.status, 200) << answer.body;
    ASSERT_TRUE(isJpeg(answer.body));
    EXPECT_LE(session().cacheBytes(), 200000u);
  }
  auto again = get("/api/image", {{"slope", "0.5"}});
  auto cached = get("/api/image", {{"slope", "0.5"}});
  EXPECT_EQ(cached.headers["X-Lfcam-Cached"], "1");
  EXPECT_EQ(again.body, cached.body);
}

TEST(ViewerSession, SlowLayersAreComputedOnceAndReportProgress) {
  EXPECT_NE(session().statusJson().find("\"depth\""), std::string::npos);
  auto depth = get("/api/image", {{"layer", "depth"}});
  ASSERT_EQ(depth.status, 200) << depth.body;
  EXPECT_TRUE(isJpeg(depth.body));
  EXPECT_NE(session().statusJson().find("\"ready\""), std::string::npos);
}

TEST(ViewerSession, TiltAnswerIsTheLibrarysTiltedRenderOfTheThreePoints) {
  const std::array<ImagePoint, 3> points = {{{10.5, 40.5}, {50.5, 12.5}, {52.5, 50.5}}};
  auto answer = get("/api/image", {{"focus-plane", "10.5,40.5:50.5,12.5:52.5,50.5"}});
  ASSERT_EQ(answer.status, 200) << answer.body;
  // Each point at its sharpest over the slider's range, as a click focuses it.
  const LightField& lf = session().lightField();
  auto plane = focusPlaneThroughPoints(lf, points, session().focusSearch());
  ASSERT_TRUE(plane.ok());
  auto expected = encodeImage(refocusTilted(lf, *plane), {.format = EncodedFormat::Jpeg, .jpegQuality = 80});
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(answer.body, *expected);
  EXPECT_NEAR(std::stod(answer.headers["X-Lfcam-Slope"]), plane->slope, 1e-5);
  double slope = 0, gx = 0, gy = 0;
  ASSERT_EQ(std::sscanf(answer.headers["X-Lfcam-Plane"].c_str(), "%lf,%lf,%lf", &slope, &gx, &gy), 3);
  EXPECT_NEAR(gx, plane->gradientX, 1e-7);
  EXPECT_NEAR(gy, plane->gradientY, 1e-7);
  // The scene's planes lie at different depths: the three points do not share one slope.
  EXPECT_GT(std::hypot(gx, gy), 1e-4);
  // Asked again: from the cache, the plane still reported.
  auto again = get("/api/image", {{"focus-plane", "10.5,40.5:50.5,12.5:52.5,50.5"}});
  EXPECT_EQ(again.headers["X-Lfcam-Cached"], "1");
  EXPECT_EQ(again.headers["X-Lfcam-Plane"], answer.headers["X-Lfcam-Plane"]);
  EXPECT_EQ(again.body, answer.body);
}

TEST(ViewerSession, UpsampledAnswerIsTheLibrarysFinerGrid) {
  const LightField& lf = session().lightField();
  for (const char* factor : {"2", "3"}) {
    auto answer = get("/api/image", {{"slope", "0.4"}, {"upsample", factor}});
    ASSERT_EQ(answer.status, 200) << answer.body;
    auto photo = refocusUpsampled(lf, 0.4, std::stoi(factor));
    ASSERT_TRUE(photo.ok());
    EXPECT_EQ(photo->width(), std::stoi(factor) * lf.ns());
    auto expected = encodeImage(*photo, {.format = EncodedFormat::Jpeg, .jpegQuality = 80});
    ASSERT_TRUE(expected.ok());
    EXPECT_EQ(answer.body, *expected) << factor;
  }
  // A click on the finer grid focuses as a plain click does.
  auto clicked = get("/api/image", {{"focus-at", "20,30"}, {"upsample", "2"}});
  ASSERT_EQ(clicked.status, 200) << clicked.body;
  EXPECT_NEAR(std::stod(clicked.headers["X-Lfcam-Slope"]), *session().focusAt(20, 30), 1e-5);
  EXPECT_NE(clicked.body, get("/api/image", {{"focus-at", "20,30"}}).body);
}

TEST(ViewerSession, FocusRangeWaitsForTheDepthMapThenIsTheLibrarysFocusSpread) {
  auto scene = smallScene();
  ViewerSession local(std::move(scene.lightField));
  const ViewerRequest range{"GET", "/api/image", {{"focus-range", "0.8:-0.2"}}};
  // The first range request computes the depth map; meanwhile another gets 202 with the progress.
  std::atomic<bool> done = false;
  ViewerAnswer first;
  std::thread computing([&] {
    first = answerRequest(local, range);
    done = true;
  });
  bool sawRunning = false;
  while (!done && !sawRunning) sawRunning = local.statusJson().find("\"running\"") != std::string::npos;
  ViewerAnswer waiting;
  if (sawRunning) waiting = answerRequest(local, range);
  computing.join();
  ASSERT_TRUE(sawRunning) << "the depth map was never seen running";
  EXPECT_EQ(waiting.status, 202) << waiting.body;
  EXPECT_NE(waiting.body.find("\"depth\""), std::string::npos);
  ASSERT_EQ(first.status, 200) << first.body;

  // The same photograph from the library: the depth map over the session's slope range.
  const LightField& lf = local.lightField();
  DepthOptions options;
  options.disparityMin = local.slopeMin();
  options.disparityMax = local.slopeMax();
  auto depth = estimateDepth(lf, options);
  ASSERT_TRUE(depth.ok());
  auto spread = refocusSpread(lf, depth->disparity, -0.2, 0.8);
  ASSERT_TRUE(spread.ok());
  auto expected = encodeImage(*spread, {.format = EncodedFormat::Jpeg, .jpegQuality = 80});
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(first.body, *expected);
  // Another range needs no new depth map: answered at once.
  EXPECT_EQ(answerRequest(local, {"GET", "/api/image", {{"focus-range", "0.3:0.1"}}}).status, 200);
}

// --- The server on a socket ---

class ViewerServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<ViewerServer>(session());
    ASSERT_TRUE(server_->bind({.host = "127.0.0.1", .port = 0, .threads = 4, .timeoutSeconds = 2}).ok());
    thread_ = std::thread([this] { (void)server_->run(); });
  }
  void TearDown() override {
    server_->stop();
    thread_.join();
  }
  // Sends raw bytes, returns the status line's code (0 when the server closed without one).
  int raw(const std::string& bytes) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(std::uint16_t(server_->port()));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return -1;
    timeval timeout{5, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    (void)!send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    // Only the status line matters (a half-closed socket would make the server drop the request).
    std::string reply;
    char buffer[4096];
    for (ssize_t n; reply.find("\r\n") == std::string::npos && (n = read(fd, buffer, sizeof buffer)) > 0;)
      reply.append(buffer, std::size_t(n));
    close(fd);
    return reply.rfind("HTTP/1.1 ", 0) == 0 ? std::stoi(reply.substr(9, 3)) : 0;
  }
  httplib::Client client() { return httplib::Client("127.0.0.1", server_->port()); }

  std::unique_ptr<ViewerServer> server_;
  std::thread thread_;
};

TEST_F(ViewerServerTest, MalformedAndOversizedRequestsGet4xxAndServingGoesOn) {
  EXPECT_EQ(raw("GARBAGE\r\n\r\n") / 100, 4);
  EXPECT_EQ(raw("GET / HTTP/9.9\r\n\r\n") / 100, 4);
  EXPECT_EQ(raw("GET /api/info?" + std::string(20000, 'a') + " HTTP/1.1\r\nHost: x\r\n\r\n"), 414);
  EXPECT_EQ(raw("GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(20000, 'b') + "\r\n\r\n") / 100, 4);
  EXPECT_EQ(raw("POST /api/image HTTP/1.1\r\nHost: x\r\nContent-Length: 100000\r\n\r\n" + std::string(5000, 'c')), 413);
  EXPECT_EQ(raw("GET /%2e%2e/%2e%2e/etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n"), 404);
  EXPECT_EQ(raw("GET /api/image?slope=%ff%00 HTTP/1.1\r\nHost: x\r\n\r\n"), 400);
  auto info = client().Get("/api/info");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, 200);
  EXPECT_NE(info->body.find("\"nu\":5"), std::string::npos);
}

TEST_F(ViewerServerTest, ServesSeveralClientsAtOnce) {
  std::atomic<int> ok = 0, busy = 0, other = 0;
  std::vector<std::thread> clients;
  for (int k = 0; k < 6; ++k)
    clients.emplace_back([&, k] {
      auto c = client();
      for (int i = 0; i < 5; ++i) {
        auto answer = c.Get("/api/image?slope=" + std::to_string(0.1 * k + 0.013 * i) + "&f-number=2");
        if (answer && answer->status == 200 && isJpeg(answer->body))
          ++ok;
        else if (answer && answer->status == 503)
          ++busy;
        else
          ++other;
      }
    });
  for (auto& t : clients) t.join();
  EXPECT_EQ(other, 0);
  EXPECT_EQ(ok + busy, 30);
  EXPECT_GT(ok, 0);
}

TEST(LivingPicture, EmbedsTheStackTheIndexAndTheSweep) {
  auto scene = smallScene();
  auto html = makeLivingPicture(scene.lightField, {.maxSlices = 8, .sweepFrames = 4, .jpegQuality = 70});
  ASSERT_TRUE(html.ok()) << html.error().message;
  EXPECT_EQ(html->find("{{LFCAM_"), std::string::npos);
  EXPECT_NE(html->find(".dual input"), std::string::npos);  // the range slider's style, inlined
  EXPECT_NE(html->find("\"index\":\""), std::string::npos);
  int images = 0;
  for (std::size_t at = 0; (at = html->find("data:image/jpeg;base64,", at)) != std::string::npos; ++at) ++images;
  EXPECT_GE(images, 1 + 2 + 4);  // all in focus, at least two slices, four viewpoints
  // Self-contained: no reference to anything outside the file.
  EXPECT_EQ(html->find("src=\"http"), std::string::npos);
  EXPECT_EQ(html->find("<script src"), std::string::npos);
  EXPECT_FALSE(makeLivingPicture(LightField()).ok());
}

// The JSON in the page's data slot.
nlohmann::json pageData(const std::string& html) {
  const std::string open = "<script id=\"lfcam-data\" type=\"application/json\">";
  const auto begin = html.find(open) + open.size();
  return nlohmann::json::parse(html.substr(begin, html.find("</script>", begin) - begin));
}

TEST(LivingPicture, OpensFocusedOnTheSubjectInTheCentre) {
  // A card over the central half in front of a background that covers more of the picture, and a
  // nearer card in a corner: the page opens on the card's slice, at either of two depths, neither
  // the middle nor an end of the stack.
  for (const double subject : {-0.6, 0.75}) {
    LayeredPlanesScene scene{.nu = 5, .nv = 5, .ns = 64, .nt = 64};
    scene.planes.push_back({.disparity = -1.0, .texture = PlaneTexture::Noise, .period = 8});
    scene.planes.push_back({.disparity = subject,
                            .texture = PlaneTexture::Checkerboard,
                            .period = 6,
                            .x0 = 14,
                            .y0 = 14,
                            .x1 = 50,
                            .y1 = 50});
    scene.planes.push_back(
        {.disparity = 1.5, .texture = PlaneTexture::Rings, .period = 6, .x0 = 0, .y0 = 0, .x1 = 12, .y1 = 12});
    auto html = makeLivingPicture(renderLayeredPlanes(scene).lightField,
                                  {.maxSlices = 8, .sweepFrames = 1, .smallAperture = false, .rangeEnds = 0});
    ASSERT_TRUE(html.ok()) << html.error().message;
    const auto data = pageData(*html);
    std::vector<double> distance;
    for (const auto& slice : data["slices"]) distance.push_back(std::abs(slice["slope"].get<double>() - subject));
    const int nearest = int(std::min_element(distance.begin(), distance.end()) - distance.begin());
    ASSERT_GT(nearest, 0);
    ASSERT_LT(nearest, int(distance.size()) - 1);
    ASSERT_NE(nearest, int(distance.size()) / 2);
    EXPECT_EQ(data["openingSlice"], nearest) << "subject at slope " << subject;
  }
}

// Every photograph of the page carries its request in the table's words (photo_request.hpp), and is
// that request's photograph: the page's controls show requests the CLI, Python and the viewer take.
TEST(LivingPicture, EveryPhotographIsItsRequestsPhotograph) {
  auto scene = smallScene();
  auto html =
      makeLivingPicture(scene.lightField, {.maxSlices = 5, .sweepFrames = 3, .jpegQuality = 70, .rangeEnds = 0});
  ASSERT_TRUE(html.ok()) << html.error().message;
  const auto data = pageData(*html);
  int checked = 0;
  for (const char* list : {"slices", "smallApertureSlices", "sweep"})
    for (const auto& photo : data[list]) {
      const std::string text = photo["request"];
      PhotoRequest request;
      for (std::size_t start = 0; start <= text.size();) {
        const std::size_t end = std::min(text.find('&', start), text.size());
        const std::string field = text.substr(start, end - start);
        ASSERT_TRUE(setPhotoField(request, field.substr(0, field.find('=')), field.substr(field.find('=') + 1)).ok())
            << text;
        start = end + 1;
      }
      auto rendered = renderPhoto(scene.lightField, request);
      ASSERT_TRUE(rendered.ok()) << text;
      auto jpeg = encodeImage(*rendered, {.format = EncodedFormat::Jpeg, .jpegQuality = 70});
      ASSERT_TRUE(jpeg.ok());
      EXPECT_EQ(photo["image"].get<std::string>(), "data:image/jpeg;base64," + base64Encode(*jpeg)) << text;
      ++checked;
    }
  EXPECT_EQ(checked, 5 + 5 + 3);
  EXPECT_NE(data["sweep"][0]["request"].get<std::string>().find("clamp=true"), std::string::npos);
}

TEST(LivingPicture, FocusRangesAreTheLibrarysFocusSpreadOverTheStacksSlopes) {
  auto scene = smallScene();
  const LivingPictureOptions options{.maxSlices = 8, .sweepFrames = 1, .jpegQuality = 70, .rangeEnds = 4};
  auto html = makeLivingPicture(scene.lightField, options);
  ASSERT_TRUE(html.ok()) << html.error().message;
  const auto data = pageData(*html);
  // Four stops from the farthest slice to the nearest, and one photograph per pair of them.
  const auto stops = data["rangeStops"].get<std::vector<int>>();
  ASSERT_EQ(stops.size(), 4u);
  EXPECT_EQ(stops.front(), 0);
  EXPECT_EQ(stops.back(), int(data["slices"].size()) - 1);
  EXPECT_TRUE(std::is_sorted(stops.begin(), stops.end()));
  ASSERT_EQ(data["ranges"].size(), 6u);
  // Each is refocusSpread between its stops' slopes, on the depth map over the stack's slopes.
  std::vector<double> slopes;
  for (const auto& slice : data["slices"]) slopes.push_back(slice["slope"]);
  DepthOptions depthOptions;
  depthOptions.disparityMin = slopes.front();
  depthOptions.disparityMax = slopes.back();
  auto depth = estimateDepth(scene.lightField, depthOptions);
  ASSERT_TRUE(depth.ok());
  for (const auto& range : data["ranges"]) {
    const int far = range["far"], near = range["near"];
    ASSERT_LT(far, near);
    auto photo = refocusSpread(scene.lightField, depth->disparity, slopes[stops[far]], slopes[stops[near]]);
    ASSERT_TRUE(photo.ok());
    auto jpeg = encodeImage(*photo, {.format = EncodedFormat::Jpeg, .jpegQuality = 70});
    ASSERT_TRUE(jpeg.ok());
    EXPECT_EQ(range["image"].get<std::string>(), "data:image/jpeg;base64," + base64Encode(*jpeg)) << far << ":" << near;
  }
  // None asked: no slider's data; one stop is refused.
  auto none = makeLivingPicture(scene.lightField, {.maxSlices = 4, .sweepFrames = 1, .rangeEnds = 0});
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->find("\"ranges\""), std::string::npos);
  EXPECT_FALSE(makeLivingPicture(scene.lightField, {.maxSlices = 4, .sweepFrames = 1, .rangeEnds = 1}).ok());
}

}  // namespace
}  // namespace lfcam
