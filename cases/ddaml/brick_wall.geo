<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "geometry.dtd">
<!-- Three courses of 2 x 1 m bricks in running bond (3, 4 and 3 bricks) on a fixed base. -->
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<Berkeley:Geometry>
   <Berkeley:Edgenodedist distance="0.001"/>
   <Jointlist>
      <Joint type="1"> -1 -1 7 -1 </Joint>
      <Joint type="1"> 7 -1 7 0 </Joint>
      <Joint type="1"> 7 0 -1 0 </Joint>
      <Joint type="1"> -1 0 -1 -1 </Joint>
      <Joint type="1"> -0.01 1 6.01 1 </Joint>
      <Joint type="1"> -0.01 2 6.01 2 </Joint>
      <Joint type="1"> -0.01 3 6.01 3 </Joint>
      <Joint type="1"> 0 -0.01 0 3.01 </Joint>
      <Joint type="1"> 6 -0.01 6 3.01 </Joint>
      <Joint type="1"> 2 -0.01 2 1.01 </Joint>
      <Joint type="1"> 4 -0.01 4 1.01 </Joint>
      <Joint type="1"> 1 0.99 1 2.01 </Joint>
      <Joint type="1"> 3 0.99 3 2.01 </Joint>
      <Joint type="1"> 5 0.99 5 2.01 </Joint>
      <Joint type="1"> 2 1.99 2 3.01 </Joint>
      <Joint type="1"> 4 1.99 4 3.01 </Joint>
   </Jointlist>
   <Fixedpointlist>
      <Point> 0 -0.5 </Point>
      <Point> 6 -0.5 </Point>
   </Fixedpointlist>
   <Measuredpointlist>
      <Point> 3 2.5 </Point>
      <Point> 0.5 1.5 </Point>
   </Measuredpointlist>
</Berkeley:Geometry>
</Berkeley:DDA>
