fn main() {
    let path = std::env::args().nth(1).unwrap();
    let path = std::path::Path::new(&path);
    let text = std::fs::read_to_string(path).unwrap();
    let (robot, _) = urdf_validator::parse::parse_urdf(&text, path).unwrap();
    let (model, _) = urdf_validator::model::Model::build(&robot);
    let options = urdf_validator::Options::default();
    let ctx = urdf_validator::checks::CheckContext {
        urdf_dir: path.parent().unwrap(),
        resolver: &options.resolver,
        meshes: &options.meshes,
    };
    let supports: Vec<_> = robot
        .links
        .iter()
        .map(|l| urdf_validator::geometry::link_supports(l, &|u| ctx.mesh_points(u)))
        .collect();
    let mut data = urdf_validator::kinematics::Data::new(&model);
    let q = model.zero_configuration();
    urdf_validator::kinematics::forward_kinematics(&model, &q, &mut data);
    for (i, l) in robot.links.iter().enumerate() {
        let low = urdf_validator::geometry::lowest_points(
            &supports[i].shapes,
            &data.link_placement[i],
            0.0,
        )
        .map(|x| x.0);
        println!(
            "{:40} shapes {} lowest {:?}",
            l.name.value,
            supports[i].shapes.len(),
            low
        );
    }
    let c = urdf_validator::classify::classify(&robot, &model, &data, &supports);
    println!(
        "{:?} wheels {:?} legs {:?} arms {}",
        c.robot_type, c.wheels, c.legs, c.arms
    );
}
