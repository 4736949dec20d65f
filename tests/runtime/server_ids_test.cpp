// The server's ids cannot be mixed up: a body, a client, a scene and a proxy each have their
// own kind, and a proxy is known by its client and its number there.
#include <gtest/gtest.h>

#include <type_traits>
#include <unordered_set>

#include "core/world/world.hpp"
#include "runtime/client_id.hpp"
#include "runtime/proxy_key.hpp"
#include "runtime/scene_registry.hpp"

namespace felt {
namespace {

template <class A, class B>
constexpr bool kMixable = std::is_convertible_v<A, B> || std::is_convertible_v<B, A>;

static_assert(!kMixable<BodyId, ClientId>);
static_assert(!kMixable<BodyId, SceneId>);
static_assert(!kMixable<BodyId, ProxyId>);
static_assert(!kMixable<ClientId, SceneId>);
static_assert(!kMixable<ClientId, ProxyId>);
static_assert(!kMixable<SceneId, ProxyId>);
static_assert(!std::is_convertible_v<ProxyKey, std::uint64_t>);

TEST(ProxyKey, NamesAProxyByItsClientAndItsNumberThere) {
  // the same number at two clients, and two numbers at one client, are three proxies
  const ProxyKey a{1, 2};
  const ProxyKey b{2, 2};
  const ProxyKey c{1, 3};
  EXPECT_NE(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a, (ProxyKey{1, 2}));
  EXPECT_LT(a, c);  // a client's proxies sort together
  EXPECT_LT(c, b);
  const std::unordered_set<ProxyKey> keys{a, b, c, ProxyKey{2, 1}, ProxyKey{1, 2}};
  EXPECT_EQ(keys.size(), 4u);
  EXPECT_TRUE(keys.contains(ProxyKey{2, 1}));
}

}  // namespace
}  // namespace felt
