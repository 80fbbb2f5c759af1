// tessera-launch: ranks from the launcher's environment, the shared-folder
// rendezvous, and whole jobs whose rank 0 renders through the nodes the
// other ranks started; the image equals a local render.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "cluster_test_util.hpp"
#include "directory_rendezvous.hpp"
#include "launch_rank.hpp"
#include "rendezvous_text.hpp"
#include "socket_rendezvous.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::cluster::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

app::EnvironmentLookup environment(std::map<std::string, std::string> values) {
  return [values = std::move(values)](const char* name) -> const char* {
    auto it = values.find(name);
    return it == values.end() ? nullptr : it->second.c_str();
  };
}

std::string launchError(const std::map<std::string, std::string>& values) {
  try {
    app::rankFromEnvironment(environment(values));
  } catch (const app::LaunchError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchRank, SlurmComesBeforeOpenMpi) {
  auto r = app::rankFromEnvironment(environment({{"SLURM_PROCID", "2"},
                                                 {"SLURM_NTASKS", "5"},
                                                 {"SLURM_JOB_ID", "77"},
                                                 {"SLURM_STEP_ID", "1"},
                                                 {"OMPI_COMM_WORLD_RANK", "0"},
                                                 {"OMPI_COMM_WORLD_SIZE", "3"}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->rank, 2u);
  EXPECT_EQ(r->size, 5u);
  EXPECT_EQ(r->job, "77.1");
  EXPECT_EQ(r->source, "slurm");
}

TEST(LaunchRank, OpenMpiWhenSlurmSaysNothing) {
  auto r = app::rankFromEnvironment(environment(
      {{"OMPI_COMM_WORLD_RANK", "1"}, {"OMPI_COMM_WORLD_SIZE", "3"}, {"OMPI_MCA_ess_base_jobid", "284229633"}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->rank, 1u);
  EXPECT_EQ(r->size, 3u);
  EXPECT_EQ(r->job, "284229633");
  EXPECT_FALSE(app::rankFromEnvironment(environment({})));
}

TEST(LaunchRank, MalformedValuesAreNamed) {
  EXPECT_THAT(launchError({{"SLURM_PROCID", "x1"}, {"SLURM_NTASKS", "2"}}), HasSubstr("SLURM_PROCID='x1'"));
  EXPECT_THAT(launchError({{"SLURM_PROCID", "-1"}, {"SLURM_NTASKS", "2"}}), HasSubstr("SLURM_PROCID"));
  EXPECT_THAT(launchError({{"SLURM_PROCID", "3"}, {"SLURM_NTASKS", "3"}}), HasSubstr("not below the job size 3"));
  EXPECT_THAT(launchError({{"OMPI_COMM_WORLD_RANK", "0"}, {"OMPI_COMM_WORLD_SIZE", "0"}}), HasSubstr("job size 0"));
  EXPECT_THAT(launchError({{"OMPI_COMM_WORLD_RANK", "0"}, {"OMPI_COMM_WORLD_SIZE", "99999999999"}}),
              HasSubstr("OMPI_COMM_WORLD_SIZE"));
  EXPECT_THAT(launchError({{"OMPI_COMM_WORLD_RANK", "0"}}), HasSubstr("OMPI_COMM_WORLD_SIZE is not set"));
}

TEST(DirectoryRendezvous, GathersInRankOrder) {
  TempDir dir;
  app::DirectoryRendezvous meet(dir.path, "job-1");
  meet.publish(2, parseNodeAddress("host-b:7002"));
  meet.publish(1, parseNodeAddress("host-a:7001"));
  auto addresses = meet.gather(3, std::chrono::milliseconds(100));
  ASSERT_EQ(addresses.size(), 2u);
  EXPECT_EQ(addresses[0].text(), "host-a:7001");
  EXPECT_EQ(addresses[1].text(), "host-b:7002");
  EXPECT_FALSE(meet.done());
  meet.markDone();
  EXPECT_TRUE(app::DirectoryRendezvous(dir.path, "job-1").done());
  EXPECT_FALSE(app::DirectoryRendezvous(dir.path, "job-2").done());
}

TEST(DirectoryRendezvous, ABoundedWaitNamesTheMissingRanks) {
  TempDir dir;
  app::DirectoryRendezvous meet(dir.path, "j");
  meet.publish(2, parseNodeAddress("127.0.0.1:7002"));
  try {
    meet.gather(5, std::chrono::milliseconds(150));
    FAIL() << "gather returned without ranks 1, 3, 4";
  } catch (const app::LaunchError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ranks 1, 3, 4 published no address"));
    EXPECT_THAT(e.what(), HasSubstr("1 of 4 nodes did"));
  }
}

TEST(DirectoryRendezvous, HostileFilesAndJobNamesAreRefused) {
  TempDir dir;
  EXPECT_THROW(app::DirectoryRendezvous(dir.path, "../up"), app::LaunchError);
  EXPECT_THROW(app::DirectoryRendezvous(dir.path, ""), app::LaunchError);
  app::DirectoryRendezvous meet(dir.path, "j");
  fs::create_directories(meet.folder());
  std::ofstream(meet.folder() / "rank-1.addr") << "no port here\n";
  EXPECT_THROW(meet.gather(2, std::chrono::milliseconds(100)), app::LaunchError);
  std::ofstream(meet.folder() / "rank-1.addr") << std::string(1000, 'a') << ":1\n";
  try {
    meet.gather(2, std::chrono::milliseconds(100));
    FAIL();
  } catch (const app::LaunchError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bytes, not one HOST:PORT line"));
  }
}

// Addresses go on to the client's command line as --nodes A,B: one that
// would split there, or carry more than one line, is refused.
TEST(RendezvousText, AddressesAreOneHostAndPortOrNothing) {
  EXPECT_EQ(app::parseAddressFile("host-a:7001\n", "f").text(), "host-a:7001");
  EXPECT_EQ(app::parseAddressFile("::1:7002", "f").host, "::1");
  for (const char* bad : {"a,b:7001\n", "a b:7001\n", "host-a:7001\nhost-b:7002\n", "host-a:0\n", ":7001\n", ""})
    EXPECT_THROW(app::parseAddressFile(bad, "f"), app::LaunchError) << bad;
  const auto line = app::parseRankLine("rank 3 host-c:7003", 4);
  ASSERT_TRUE(line);
  EXPECT_EQ(line->rank, 3u);
  EXPECT_EQ(line->address.text(), "host-c:7003");
  for (const char* bad : {"rank 4 host:1", "rank 0 host:1", "rank 1 a,b:1", "rank 1 host:1 extra", "rank x host:1"})
    EXPECT_FALSE(app::parseRankLine(bad, 4)) << bad;
}

// A port that was free a moment ago (the socket rendezvous needs one every rank knows).
std::uint16_t freePort() {
  int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof a;
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
  close(fd);
  return ntohs(a.sin_port);
}

TEST(SocketRendezvous, GathersTheNodesThatConnectAndTellsThemWhenDone) {
  const NodeAddress rankZero{"127.0.0.1", freePort()};
  app::SocketRendezvous server(rankZero, true, std::chrono::seconds(5));
  app::SocketRendezvous first(rankZero, false, std::chrono::seconds(5)),
      second(rankZero, false, std::chrono::seconds(5));
  std::thread late([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    second.publish(2, parseNodeAddress("host-b:7002"));
  });
  first.publish(1, parseNodeAddress("host-a:7001"));
  auto addresses = server.gather(3, std::chrono::seconds(5));
  late.join();
  ASSERT_EQ(addresses.size(), 2u);
  EXPECT_EQ(addresses[0].text(), "host-a:7001");
  EXPECT_EQ(addresses[1].text(), "host-b:7002");
  EXPECT_FALSE(first.done());
  server.markDone();
  for (int i = 0; i < 100 && !(first.done() && second.done()); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(first.done());
  EXPECT_TRUE(second.done());
}

TEST(SocketRendezvous, StrayLinesAreRefusedAndTheWaitNamesWhoIsMissing) {
  const NodeAddress rankZero{"127.0.0.1", freePort()};
  auto server = std::make_unique<app::SocketRendezvous>(rankZero, true, std::chrono::seconds(5));
  app::SocketRendezvous impostor(rankZero, false, std::chrono::seconds(5)),
      real(rankZero, false, std::chrono::seconds(5));
  impostor.publish(9, parseNodeAddress("evil:1"));  // rank 9 of a job of 3
  real.publish(2, parseNodeAddress("127.0.0.1:7002"));
  try {
    server->gather(3, std::chrono::milliseconds(300));
    FAIL() << "gather returned without rank 1";
  } catch (const app::LaunchError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rank 1 published no address in rank 0 at " + rankZero.text()));
    EXPECT_THAT(e.what(), HasSubstr("refused 'rank 9 evil:1'"));
  }
  server.reset();  // rank 0 gone: a node that comes now gives up after its wait
  EXPECT_THROW(app::SocketRendezvous(rankZero, false, std::chrono::milliseconds(200)).publish(1, rankZero),
               app::LaunchError);
}

struct Run {
  int status = -1;
  std::string err;
};

// bash and mpirun are not ours: they run without the asan test preset's
// preload of the ASan runtime, which fails them on their own leaks at exit
// (tests/sanitizers/outside.sh). What they start is ours and carries its own.
const std::string kOutside = "env -u LD_PRELOAD ";

Run shell(const std::string& command, const fs::path& errFile) {
  const int raw = std::system((command + " > /dev/null 2> '" + errFile.string() + "' < /dev/null").c_str());
  std::ifstream in(errFile);
  std::stringstream s;
  s << in.rdbuf();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, s.str()};
}

const std::string kLaunch = TSR_LAUNCH_BINARY;
const std::string kRender = TSR_RENDER_BINARY;

TEST(LaunchCommand, WithoutARankItIsAUsageError) {
  TempDir dir;
  auto r = shell(
      "env -u SLURM_PROCID -u OMPI_COMM_WORLD_RANK " + kLaunch + " --rendezvous " + dir.path.string() + " -- true",
      dir.path / "err");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("error: no rank", 0), 0u) << r.err;
}

TEST(LaunchCommand, RankZeroGivesUpNamingTheRanksThatNeverCame) {
  TempDir dir;
  auto r = shell(kLaunch + " --rendezvous " + dir.path.string() + " --rank 0 --size 3 --job lonely --wait 0.3 -- true",
                 dir.path / "err");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("error: rank 0: ranks 1, 2 published no address"));
  EXPECT_TRUE(fs::exists(dir.path / "tessera-lonely" / "done"));  // any node that comes late stops again
}

// The client: builtin:cornell on the job's nodes, cooperatively on two or
// as a 2x2 wall on four (the nodes' addresses come from tessera-launch).
std::string clientCommand(const fs::path& dir, bool wall = false) {
  std::ofstream(dir / "cluster.json") << R"({"mode": ")" << (wall ? "tiled" : "cooperative") << R"(",
    "backend": "embree", "parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1},
    "nodes": [)" << (wall ? "{}, {}, {}, {}" : "{}, {}")
                                      << R"(], "cooperative": {"tileSize": 16}, "wall": {"columns": 2, "rows": 2}})";
  return kRender + " builtin:cornell --quiet --size 48x40 --cluster " + (dir / "cluster.json").string() + " --output " +
         (dir / "cluster.exr").string();
}

void expectEqualsLocalRender(const fs::path& dir) {
  ASSERT_EQ(std::system((kRender +
                         " builtin:cornell --quiet --spp 2 --max-depth 3 --seed 5 --threads 1 --size 48x40 "
                         "--output " +
                         (dir / "local.exr").string())
                            .c_str()),
            0);
  EXPECT_TRUE(
      bitwiseEqual(med::readImage((dir / "cluster.exr").string()), med::readImage((dir / "local.exr").string())));
}

TEST(LaunchCommand, ThreeSlurmRanksRenderLikeALocalRender) {
  // What srun does: the same command three times, ranks in SLURM_PROCID.
  TempDir dir;
  TokenFile token("launch token");
  std::string script;
  for (int rank = 2; rank >= 0; --rank)  // nodes first or last must not matter
    script += "env SLURM_PROCID=" + std::to_string(rank) + " SLURM_NTASKS=3 SLURM_JOB_ID=42 " + kLaunch +
              " --rendezvous " + dir.path.string() + " --token-file " + token.path() + " --threads 1 -- " +
              clientCommand(dir.path) + (rank ? " &\n" : "\n");
  script += "status=$?; wait; exit $status\n";
  std::ofstream(dir.path / "job.sh") << script;
  auto r = shell(kOutside + "bash " + (dir.path / "job.sh").string(), dir.path / "err");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("2 of 2 nodes published"));
  EXPECT_FALSE(fs::exists(dir.path / "tessera-42.0")) << "the nodes retired and rank 0 removed the folder";
  EXPECT_FALSE(fs::exists(dir.path / "tessera-42"));
  expectEqualsLocalRender(dir.path);
}

TEST(LaunchCommand, RanksGivenByHandMeetAtRankZerosAddress) {
  // What an ssh loop does: --rank/--size on each command line, no shared folder.
  TempDir dir;
  TokenFile token("launch token");
  const std::string meet = " --rendezvous-address 127.0.0.1:" + std::to_string(freePort());
  std::string script;
  for (int rank = 2; rank >= 0; --rank)  // the nodes start first and retry until rank 0 listens
    script += kLaunch + meet + " --rank " + std::to_string(rank) + " --size 3 --token-file " + token.path() +
              " --threads 1 -- " + clientCommand(dir.path) + (rank ? " &\n" : "\n");
  script += "status=$?; wait; exit $status\n";
  std::ofstream(dir.path / "job.sh") << script;
  auto r = shell(kOutside + "bash " + (dir.path / "job.sh").string(), dir.path / "err");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("2 of 2 nodes published"));
  expectEqualsLocalRender(dir.path);
}

#ifdef TSR_MPIRUN
TEST(LaunchCommand, MpirunOnLoopbackRendersAWallLikeALocalRender) {
  // Five processes: the client and the four nodes of a 2x2 wall.
  TempDir dir;
  TokenFile token("launch token");
  auto r = shell(kOutside + TSR_MPIRUN + " --allow-run-as-root --oversubscribe -np 5 " + kLaunch + " --rendezvous " +
                     dir.path.string() + " --token-file " + token.path() + " --threads 1 -- " +
                     clientCommand(dir.path, true),
                 dir.path / "err");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("[rank 0/5]: running"));
  EXPECT_THAT(r.err, HasSubstr("4 of 4 nodes published"));
  for (const auto& entry : fs::directory_iterator(dir.path))
    EXPECT_NE(entry.path().filename().string().rfind("tessera-", 0), 0u) << entry.path() << " left behind";
  expectEqualsLocalRender(dir.path);
}
#endif

}  // namespace
}  // namespace tsr::cluster::test
